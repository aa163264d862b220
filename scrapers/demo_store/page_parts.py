"""What every demo-store page shares: the store's furniture (header, navigation, an Organization JSON-LD
block, footer), labels per language, numbers written as the page's language writes them, prices, and a
"you may also like" widget with other products' sizes (a trap for extractors reading all text).
"""

from __future__ import annotations

import json
from html import escape

from scrapers.demo_store.products import PRODUCTS, DemoProduct

__all__ = [
    "AMAZON_UNITS", "DECIMAL_COMMA", "LABELS", "STORE_NAME", "UNECE", "escape", "furnished_page", "num",
    "price_text", "quantitative_value", "related_widget", "spec_label",
]

STORE_NAME = "Demo Home Store"
UNECE = {"cm": "CMT", "mm": "MMT", "m": "MTR", "in": "INH", "g": "GRM", "kg": "KGM", "oz": "ONZ", "lb": "LBR"}
DECIMAL_COMMA = {"de", "fr", "es", "it", "pt"}

# fmt: off
#: Labels of spec tables, per language.
LABELS: dict[str, dict[str, str]] = {
    "en": {"width": "Width", "depth": "Depth", "height": "Height", "length": "Length", "weight": "Weight",
           "material": "Material", "specs": "Specifications", "price": "Price"},
    "de": {"width": "Breite", "depth": "Tiefe", "height": "Höhe", "length": "Länge", "weight": "Gewicht",
           "material": "Material", "specs": "Produktdetails", "price": "Preis"},
    "fr": {"width": "Largeur", "depth": "Profondeur", "height": "Hauteur", "length": "Longueur", "weight": "Poids",
           "material": "Matière", "specs": "Caractéristiques", "price": "Prix"},
    "es": {"width": "Ancho", "depth": "Fondo", "height": "Alto", "length": "Largo", "weight": "Peso",
           "material": "Material", "specs": "Especificaciones", "price": "Precio"},
    "it": {"width": "Larghezza", "depth": "Profondità", "height": "Altezza", "length": "Lunghezza",
           "weight": "Peso", "material": "Materiale", "specs": "Caratteristiche", "price": "Prezzo"},
    "pt": {"width": "Largura", "depth": "Profundidade", "height": "Altura", "length": "Comprimento",
           "weight": "Peso", "material": "Material", "specs": "Especificações", "price": "Preço"},
}
# fmt: on
AMAZON_UNITS = {"in": "inches", "cm": "cm", "oz": "Ounces", "lb": "Pounds", "g": "g", "kg": "Kilograms"}


def num(value: float, lang: str = "en") -> str:
    """A number as the page's language writes it (decimal comma where usual, no trailing zeros)."""
    text = f"{value:.4f}".rstrip("0").rstrip(".")
    return text.replace(".", ",") if lang in DECIMAL_COMMA else text


def price_text(prod: DemoProduct) -> str:
    cents = 499 + (sum(map(ord, prod.handle)) * 37) % 6000
    return f"{cents // 100}.{cents % 100:02d}"


def related_widget(prod: DemoProduct) -> str:
    """A comparison widget with two other products' sizes: a trap for extractors reading all text."""
    others = [p for p in PRODUCTS if p.handle != prod.handle][sum(map(ord, prod.handle)) % 10 :][:2]
    items = "".join(
        f'<li class="related-item"><a href="{p.path}">{escape(p.title)}</a> '
        f'<span class="related-size">{" x ".join(num(d, prod.lang) for d in p.dims)} {p.dim_unit}</span></li>'
        for p in others
    )
    return f'<aside class="related-products"><h2>You may also like</h2><ul>{items}</ul></aside>'


def furnished_page(prod_title: str, lang: str, canonical: str, head: str, main: str, aside: str = "") -> str:
    org = json.dumps(
        {
            "@context": "https://schema.org",
            "@type": "Organization",
            "name": STORE_NAME,
            "url": canonical.split("/", 3)[0] + "//" + canonical.split("/", 3)[2],
        }
    )
    return (
        f'<!DOCTYPE html>\n<html lang="{lang}">\n<head>\n<meta charset="utf-8">\n'
        f"<title>{escape(prod_title)} | {STORE_NAME}</title>\n"
        f'<link rel="canonical" href="{escape(canonical)}">\n'
        f'<meta property="og:title" content="{escape(prod_title)}">\n<meta property="og:type" content="product">\n'
        f'<meta property="og:url" content="{escape(canonical)}">\n'
        f'<script type="application/ld+json">{org}</script>\n{head}</head>\n<body>\n'
        f'<header><nav><a href="/">{STORE_NAME}</a> <a href="/about.html">About</a> '
        f'<a href="/cart">Cart (0)</a></nav></header>\n<main>\n{main}\n</main>\n{aside}\n'
        f"<footer><p>&copy; 2026 {STORE_NAME}. Free shipping over 50.</p></footer>\n</body>\n</html>\n"
    )


def spec_label(prod: DemoProduct, i: int) -> str:
    return LABELS[prod.lang][prod.dim_labels[i]]


def quantitative_value(value: float, unit: str) -> dict:
    return {"@type": "QuantitativeValue", "value": value, "unitCode": UNECE[unit]}
