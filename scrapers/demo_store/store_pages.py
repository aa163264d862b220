"""The demo store's pages that are not a product's: the broken pages served with status 200 (malformed
JSON-LD, absurd values, a page that is no product, a disallowed and a slow product), the home page and
the sitemap.
"""

from __future__ import annotations

import json

from scrapers.demo_store.page_parts import STORE_NAME, escape, furnished_page, quantitative_value
from scrapers.demo_store.products import BrokenPage

__all__ = ["render_broken", "render_home", "render_sitemap"]


def render_broken(page: BrokenPage, base: str) -> str:
    """The body of a broken page that is served with status 200 (the others are produced by the server)."""
    url = base + page.path
    if page.kind == "malformed_jsonld":
        head = (
            '<script type="application/ld+json">{"@context": "https://schema.org", "@type": "Product", '
            '"name": "Broken Jar", "weight": {"@type": "QuantitativeValue", "value": 1,, "unitCode": "KGM"}'
            "</script>\n"
        )
        return furnished_page("Broken Jar", "en", url, head, "<p>This page's product data is broken.</p>")
    if page.kind == "absurd":
        data = {
            "@context": "https://schema.org",
            "@type": "Product",
            "name": "Giant Mug",
            "url": url,
            "height": quantitative_value(40, "m"),
            "width": quantitative_value(12, "cm"),
            "depth": quantitative_value(9, "cm"),
            "weight": quantitative_value(350, "g"),
        }
        head = f'<script type="application/ld+json">{json.dumps(data)}</script>\n'
        return furnished_page("Giant Mug", "en", url, head, "<h1>Giant Mug</h1><p>Height: 40 m. Weight: 350 g.</p>")
    if page.kind == "not_product":
        return furnished_page(
            "About us",
            "en",
            url,
            "",
            "<h1>About us</h1><p>We have sold kitchen and home goods since 2011. "
            "Our warehouse is 40 x 25 m and ships 300 parcels a day.</p>",
        )
    if page.kind in ("disallowed", "slow"):
        name = "Staff Desk Lamp" if page.kind == "disallowed" else "Slow Teapot"
        data = {
            "@context": "https://schema.org",
            "@type": "Product",
            "name": name,
            "url": url,
            "height": quantitative_value(20, "cm"),
            "width": quantitative_value(15, "cm"),
            "depth": quantitative_value(12, "cm"),
            "weight": quantitative_value(800, "g"),
        }
        head = f'<script type="application/ld+json">{json.dumps(data)}</script>\n'
        return furnished_page(name, "en", url, head, f"<h1>{name}</h1>")
    raise ValueError(f"{page.kind} pages are not rendered as HTML")


def render_home(paths: list[tuple[str, str]], base: str) -> str:
    links = "".join(f'<li><a href="{p}">{escape(t)}</a></li>' for p, t in paths)
    return furnished_page(STORE_NAME, "en", base + "/", "", f"<h1>{STORE_NAME}</h1><ul>{links}</ul>")


def render_sitemap(paths: list[tuple[str, str]], base: str) -> str:
    """``paths``: (path, lastmod date) pairs."""
    urls = "".join(f"<url><loc>{escape(base + p)}</loc><lastmod>{d}</lastmod></url>\n" for p, d in paths)
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<urlset xmlns="http://www.sitemaps.org/schemas/sitemap/0.9">\n{urls}</urlset>\n'
    )
