"""Storefront scrapers and the nightly catalog ingestion job."""
