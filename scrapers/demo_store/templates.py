"""Page templates of the demo store: one function per storefront format, shaped like real stores' pages.

Every function takes a :class:`~scrapers.demo_store.products.DemoProduct` and the store's base URL and
returns the HTML text (or JSON text for Shopify's ``.json`` endpoint). The pages carry the furniture real
pages carry (:mod:`scrapers.demo_store.page_parts`: navigation, price, breadcrumbs, an Organization JSON-LD
block, a "you may also like" widget with other products' sizes) so extractors meet the same traps as on the
web. The store's other pages (broken pages, home, sitemap) are :mod:`scrapers.demo_store.store_pages`.
"""

from __future__ import annotations

import json

from scrapers.demo_store.page_parts import (
    AMAZON_UNITS,
    LABELS,
    UNECE,
    escape,
    furnished_page,
    num,
    price_text,
    quantitative_value,
    related_widget,
    spec_label,
)
from scrapers.demo_store.products import DemoProduct

__all__ = ["RENDERERS", "render_product", "render_shopify_json"]


# -------------------------------------------------------------------------------- schema.org formats
def _schema_product(prod: DemoProduct, url: str) -> dict:
    data: dict = {
        "@type": "Product",
        "@id": url + "#product",
        "name": prod.title,
        "url": url,
        "sku": prod.handle.upper()[:12],
        "description": prod.description or f"{prod.title} made of {prod.material_text}.",
        "brand": {"@type": "Brand", "name": "Demo Home"},
        "offers": {
            "@type": "Offer",
            "price": price_text(prod),
            "priceCurrency": "EUR",
            "availability": "https://schema.org/InStock",
        },
    }
    if prod.gtin:
        data["gtin13"] = prod.gtin
    if prod.material_text:
        data["material"] = prod.material_text
    props = {"width": "width", "depth": "depth", "length": "depth", "height": "height"}
    for label, value in zip(prod.dim_labels, prod.dims, strict=True):
        data[props[label]] = quantitative_value(value, prod.dim_unit)
    if prod.mass is not None:
        data["weight"] = quantitative_value(prod.mass, prod.mass_unit)
    return data


def _visible_basics(prod: DemoProduct) -> str:
    lab = LABELS[prod.lang]
    return (
        f'<nav class="breadcrumbs"><a href="/">Home</a> / <a href="/kitchen">Kitchen</a></nav>\n'
        f'<h1 class="product-title">{escape(prod.title)}</h1>\n'
        f'<p class="price">{lab["price"]}: €{price_text(prod)}</p>\n'
        f'<button class="add-to-cart">Add to cart</button>\n'
    )


def jsonld(prod: DemoProduct, base: str) -> str:
    url = base + prod.path
    blocks = []
    if prod.handle == "ceramic-salad-bowl":
        # One malformed block before the good one: it must not hide the other.
        blocks.append(
            '<script type="application/ld+json">{"@context": "https://schema.org", "@type": '
            '"BreadcrumbList", "itemListElement": [{"@type": "ListItem",, }]</script>'
        )
    if prod.fmt == "jsonld_graph":
        product = _schema_product(prod, url)
        graph = {
            "@context": "https://schema.org",
            "@graph": [
                {"@type": "WebPage", "@id": url, "url": url, "name": prod.title},
                {
                    "@type": "BreadcrumbList",
                    "itemListElement": [
                        {"@type": "ListItem", "position": 1, "name": "Home", "item": base + "/"}
                    ],
                },
                product,
            ],
        }
        blocks.append(f'<script type="application/ld+json">{json.dumps(graph, ensure_ascii=False)}</script>')
    else:
        product = {"@context": "https://schema.org", **_schema_product(prod, url)}
        blocks.append(
            f'<script type="application/ld+json">{json.dumps(product, ensure_ascii=False)}</script>'
        )
    main = (
        _visible_basics(prod)
        + f'<div class="description"><p>{escape(prod.title)} in {escape(prod.material_text or "")}.</p></div>'
    )
    return furnished_page(prod.title, prod.lang, url, "\n".join(blocks) + "\n", main, related_widget(prod))


def microdata(prod: DemoProduct, base: str) -> str:
    url = base + prod.path
    props = {"width": "width", "depth": "depth", "length": "depth", "height": "height"}
    dims = "".join(
        f'<li>{spec_label(prod, i)}: <span itemprop="{props[label]}" itemscope '
        f'itemtype="https://schema.org/QuantitativeValue"><span itemprop="value">{num(v)}</span> '
        f'<meta itemprop="unitCode" content="{UNECE[prod.dim_unit]}">{prod.dim_unit}</span></li>'
        for i, (label, v) in enumerate(zip(prod.dim_labels, prod.dims, strict=True))
    )
    weight = (
        f'<li>Weight: <span itemprop="weight" itemscope itemtype="https://schema.org/QuantitativeValue">'
        f'<span itemprop="value">{num(prod.mass)}</span> <meta itemprop="unitCode" '
        f'content="{UNECE[prod.mass_unit]}">{prod.mass_unit}</span></li>'
        if prod.mass is not None
        else ""
    )
    main = (
        f'<div itemscope itemtype="https://schema.org/Product">\n'
        f'<h1 itemprop="name">{escape(prod.title)}</h1>\n<link itemprop="url" href="{url}">\n'
        + (f'<meta itemprop="gtin13" content="{prod.gtin}">\n' if prod.gtin else "")
        + f'<div itemprop="offers" itemscope itemtype="https://schema.org/Offer"><span itemprop="price" '
        f'content="{price_text(prod)}">€{price_text(prod)}</span><meta itemprop="priceCurrency" content="EUR"></div>\n'
        f'<p itemprop="description">A {escape(prod.title.lower())} for every day.</p>\n'
        f'<h2>Specifications</h2><ul class="specs">{dims}{weight}'
        f'<li>Material: <span itemprop="material">{escape(prod.material_text or "")}</span></li></ul>\n</div>'
    )
    return furnished_page(prod.title, prod.lang, url, "", main, related_widget(prod))


# -------------------------------------------------------------------------------- Shopify
def _shopify_grams(prod: DemoProduct) -> int:
    if prod.extra.get("grams_zero") or prod.mass_g is None:
        return 0
    return round(prod.mass_g)


def _shopify_body(prod: DemoProduct) -> str:
    dims = " x ".join(num(d) for d in prod.dims)
    body = (
        f"<p>{escape(prod.title)}, made of {escape(prod.material_text or '')}.</p><p>Size: {dims} {prod.dim_unit}</p>"
    )
    if prod.extra.get("grams_zero") and prod.mass is not None:
        body += f"<p>Weight: {num(prod.mass)} {prod.mass_unit}</p>"
    return body


def shopify_product_json(prod: DemoProduct, base: str) -> dict:
    grams = _shopify_grams(prod)
    weight = 0.0 if grams == 0 else prod.mass
    unit = prod.mass_unit if prod.mass_unit in ("g", "kg", "lb", "oz") else "g"
    pid = 7000000000 + sum(map(ord, prod.handle)) * 1000
    return {
        "id": pid,
        "title": prod.title,
        "handle": prod.handle,
        "body_html": _shopify_body(prod),
        "vendor": "Demo Home",
        "product_type": "Home",
        "tags": "home, demo",
        "variants": [
            {
                "id": pid + 1,
                "product_id": pid,
                "title": "Default Title",
                "price": price_text(prod),
                "sku": prod.handle.upper()[:12],
                "barcode": prod.gtin or "",
                "grams": grams,
                "weight": weight,
                "weight_unit": unit,
                "requires_shipping": True,
            }
        ],
        "options": [{"name": "Title", "values": ["Default Title"]}],
    }


def render_shopify_json(prod: DemoProduct, base: str) -> str:
    return json.dumps({"product": shopify_product_json(prod, base)}, ensure_ascii=False)


def shopify(prod: DemoProduct, base: str) -> str:
    url = base + prod.path
    pj = json.dumps(shopify_product_json(prod, base), ensure_ascii=False).replace("</", "<\\/")
    main = (
        f'<div class="product-single">\n<h1 class="product-single__title">{escape(prod.title)}</h1>\n'
        f'<span class="product-single__price">€{price_text(prod)}</span>\n'
        f'<div class="product-single__description rte">{_shopify_body(prod)}</div>\n'
        f'<script type="application/json" id="ProductJson-product-template">{pj}</script>\n</div>'
    )
    return furnished_page(prod.title, prod.lang, url, "", main, related_widget(prod))


# -------------------------------------------------------------------------------- WooCommerce
def woocommerce(prod: DemoProduct, base: str) -> str:
    url = base + prod.path
    dims_html = " &times; ".join(num(d) for d in prod.dims) + f" {prod.dim_unit}"
    weight_html = f"{num(prod.mass)} {prod.mass_unit}" if prod.mass is not None else ""
    keys = {"length": "length", "width": "width", "height": "height", "depth": "width"}
    variation = {
        "variation_id": 100 + len(prod.handle),
        "attributes": {"attribute_pa_finish": "natural"},
        "display_price": float(price_text(prod)),
        "is_in_stock": True,
        "sku": prod.handle.upper()[:12],
        "weight": num(prod.mass) if prod.mass is not None else "",
        "weight_html": weight_html or "N/A",
        "dimensions": {keys[label]: num(v) for label, v in zip(prod.dim_labels, prod.dims, strict=True)},
        "dimensions_html": dims_html.replace("&times;", "\u00d7"),
    }
    variations = escape(json.dumps([variation], ensure_ascii=False), quote=True)
    rows = [
        ("weight", "Weight", weight_html),
        ("dimensions", "Dimensions", dims_html),
        ("attribute_pa_material", "Material", f"<p>{escape(prod.material_text or '')}</p>"),
    ]
    table = "".join(
        f'<tr class="woocommerce-product-attributes-item woocommerce-product-attributes-item--{key}">'
        f'<th class="woocommerce-product-attributes-item__label">{label}</th>'
        f'<td class="woocommerce-product-attributes-item__value">{value}</td></tr>'
        for key, label, value in rows
        if value
    )
    main = (
        f'<div id="product-{len(prod.handle)}" class="product type-product status-publish has-weight has-dimensions">\n'
        f'<h1 class="product_title entry-title">{escape(prod.title)}</h1>\n'
        f'<p class="price"><span class="woocommerce-Price-amount amount">€{price_text(prod)}</span></p>\n'
        f'<form class="variations_form cart" action="{url}" method="post" '
        f'data-product_id="{len(prod.handle)}" data-product_variations="{variations}">\n'
        f'<select name="attribute_pa_finish"><option value="natural">Natural</option></select></form>\n'
        f'<div class="woocommerce-tabs"><div id="tab-additional_information"><h2>Additional information</h2>\n'
        f'<table class="woocommerce-product-attributes shop_attributes">{table}</table></div></div>\n</div>'
    )
    return furnished_page(prod.title, prod.lang, url, "", main, related_widget(prod))


# -------------------------------------------------------------------------------- Amazon
def _amazon_bullet(label: str, value: str) -> str:
    # Amazon writes "Label &rlm; : &lrm; value" with invisible direction marks around the colon.
    return (
        f'<li><span class="a-list-item"><span class="a-text-bold">{label} \u200f : \u200e</span> '
        f"<span>{value}</span></span></li>"
    )


def amazon(prod: DemoProduct, base: str) -> str:
    url = base + prod.path
    es = prod.lang == "es"
    dims = " x ".join(num(d, prod.lang) for d in prod.dims) + " " + AMAZON_UNITS[prod.dim_unit]
    mass = f"{num(prod.mass, prod.lang)} {AMAZON_UNITS[prod.mass_unit]}" if prod.mass is not None else ""
    bullets = []
    if prod.package:
        # Product dimensions alone, weight as its own bullet, package values separately.
        bullets.append(_amazon_bullet("Product Dimensions", dims))
        bullets.append(_amazon_bullet("Item Weight", mass))
        for pdims, pmass in prod.package:
            pd = " x ".join(num(d, prod.lang) for d in pdims) + " " + AMAZON_UNITS[prod.dim_unit]
            bullets.append(
                _amazon_bullet("Package Dimensions", f"{pd}; {num(pmass)} {AMAZON_UNITS[prod.mass_unit]}")
            )
    else:
        label = "Dimensiones del producto" if es else "Product Dimensions"
        bullets.append(_amazon_bullet(label, f"{dims}; {mass}"))
    bullets.append(_amazon_bullet("Fabricante" if es else "Manufacturer", "Demo Home"))
    bullets.append(_amazon_bullet("ASIN", "B0" + prod.handle.upper().replace("-", "")[:8]))
    if prod.gtin:
        bullets.append(_amazon_bullet("UPC", prod.gtin[-12:]))
    main = (
        f'<div id="centerCol"><h1 id="title"><span id="productTitle">{escape(prod.title)}</span></h1>\n'
        f'<div id="corePrice_feature_div"><span class="a-price">€{price_text(prod)}</span></div>\n'
        f'<div id="feature-bullets"><ul><li>Made of {escape(prod.material_text or "")}</li>'
        f"<li>Easy to clean</li></ul></div></div>\n"
        f'<div id="detailBullets_feature_div"><ul class="a-unordered-list a-nostyle a-vertical detail-bullet-list">'
        f"{''.join(bullets)}</ul></div>"
    )
    return furnished_page(prod.title, prod.lang, url, "", main)


# -------------------------------------------------------------------------------- IKEA
def ikea(prod: DemoProduct, base: str) -> str:
    url = base + prod.path
    lab = LABELS["en"]
    meas = "".join(
        f'<p class="pip-product-dimensions__measurement-wrapper"><span class="pip-product-dimensions__measurement-name">'
        f"{lab[label]}: </span>{num(v)} {prod.dim_unit}</p>"
        for label, v in zip(prod.dim_labels, prod.dims, strict=True)
    )
    if prod.mass is not None:
        meas += (
            f'<p class="pip-product-dimensions__measurement-wrapper"><span class="pip-product-dimensions__'
            f'measurement-name">Net weight: </span>{num(prod.mass)} {prod.mass_unit}</p>'
        )
    packages = []
    for i, (pdims, pmass) in enumerate(prod.package, start=1):
        w, h, length = pdims[1], pdims[2], pdims[0]
        packages.append(
            f'<div class="pip-product-dimensions__package"><h4>Package {i} of {len(prod.package)}</h4>'
            f"<p>Article number: 40{i}.{len(prod.handle):03d}.{i}7</p>"
            f"<p>Width: {num(w)} cm</p><p>Height: {num(h)} cm</p><p>Length: {num(length)} cm</p>"
            f"<p>Weight: {num(pmass)} kg</p><p>Package(s): 1</p></div>"
        )
    main = (
        f'<div class="pip-header-section"><h1><span class="pip-header-section__title--big">{escape(prod.title)}'
        f'</span></h1><span class="pip-price">€{price_text(prod)}</span></div>\n'
        f'<div class="pip-product-details"><h3>Materials</h3><p>{escape(prod.material_text or "")}</p></div>\n'
        f'<div class="pip-product-dimensions"><h3>Product size</h3>{meas}</div>\n'
        f'<div class="pip-product-dimensions__packaging"><h3>Packaging</h3>{"".join(packages)}</div>'
    )
    return furnished_page(prod.title, prod.lang, url, "", main)


# -------------------------------------------------------------------------------- spec tables, lists, text
def _spec_rows(prod: DemoProduct) -> list[tuple[str, str]]:
    lab = LABELS[prod.lang]
    rows = [(spec_label(prod, i), f"{num(v, prod.lang)} {prod.dim_unit}") for i, v in enumerate(prod.dims)]
    if prod.mass is not None:
        rows.append((lab["weight"], f"{num(prod.mass, prod.lang)} {prod.mass_unit}"))
    if prod.material_text:
        rows.append((lab["material"], prod.material_text))
    return rows


def spec_table(prod: DemoProduct, base: str) -> str:
    url = base + prod.path
    rows = "".join(f"<tr><th>{escape(k)}</th><td>{escape(v)}</td></tr>" for k, v in _spec_rows(prod))
    main = (
        _visible_basics(prod) + f'<section class="product-specs"><h2>{LABELS[prod.lang]["specs"]}</h2>'
        f'<table class="specs">{rows}</table></section>'
    )
    return furnished_page(prod.title, prod.lang, url, "", main, related_widget(prod))


def spec_dl(prod: DemoProduct, base: str) -> str:
    url = base + prod.path
    items = "".join(f"<dt>{escape(k)}</dt><dd>{escape(v)}</dd>" for k, v in _spec_rows(prod))
    main = (
        _visible_basics(prod) + f'<section class="product-specs"><h2>{LABELS[prod.lang]["specs"]}</h2>'
        f'<dl class="specs">{items}</dl></section>'
    )
    return furnished_page(prod.title, prod.lang, url, "", main, related_widget(prod))


def free_text(prod: DemoProduct, base: str) -> str:
    url = base + prod.path
    main = _visible_basics(prod) + f'<div class="description"><p>{escape(prod.description)}</p></div>'
    return furnished_page(prod.title, prod.lang, url, "", main)


RENDERERS = {
    "jsonld": jsonld,
    "jsonld_graph": jsonld,
    "microdata": microdata,
    "shopify": shopify,
    "woocommerce": woocommerce,
    "amazon": amazon,
    "ikea": ikea,
    "spec_table": spec_table,
    "spec_dl": spec_dl,
    "free_text": free_text,
}


def render_product(prod: DemoProduct, base: str, *, canonical_path: str | None = None) -> str:
    page = RENDERERS[prod.fmt](prod, base)
    return page
