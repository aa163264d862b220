"""The demo store's products: one table that the pages are rendered from, so tests know the truth.

Each :class:`DemoProduct` holds what its page states (numbers in the page's own units and order, labels in
the page's language) and derives the truth in catalog units (cm, largest first; g). Prices and the other
page furniture are invented; the sizes and masses are those of real objects of the kind.

Formats (``fmt``), one page template each in :mod:`scrapers.demo_store.templates`:

================ ==========================================================================================
``jsonld``       schema.org Product in JSON-LD, width/height/depth/weight as QuantitativeValue + UN/CEFACT
``jsonld_graph`` the same inside an ``@graph`` next to WebPage and BreadcrumbList, in mm and kg
``microdata``    schema.org Product as microdata (itemprop attributes)
``shopify``      ``/products/<handle>`` page plus ``/products/<handle>.json`` (variants' grams/weight)
``woocommerce``  attributes table (Weight, ``L × W × H cm`` Dimensions) and a variations JSON attribute
``amazon``       detail bullets ("Product Dimensions : 9.25 x 3 x 14.85 inches; 10.56 Ounces", U+200E)
``ikea``         product measurements plus a per-package list
``spec_table``   a label/value table in the page's language, decimal commas where the language has them
``spec_dl``      the same as a definition list
``free_text``    sizes and weight only in a sentence of the description
================ ==========================================================================================

``in_seed`` marks products whose name is already in ``kb/data/seed_catalog.csv``: ingesting them updates
an existing object (new observations, fused values) instead of adding one.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["BROKEN_PAGES", "DemoProduct", "PRODUCTS", "SEARCH_ONLY_PRODUCTS", "BrokenPage", "product_by_handle"]

_TO_CM = {"cm": 1.0, "mm": 0.1, "m": 100.0, "in": 2.54}
_TO_G = {"g": 1.0, "kg": 1000.0, "oz": 28.349523125, "lb": 453.59237}


@dataclass(frozen=True)
class DemoProduct:
    """One product page of the demo store.

    ``dims`` are as the page states them, in ``dim_unit`` and in the page's order (``dim_labels`` names
    them, e.g. width, depth, height); ``mass`` in ``mass_unit``. ``package`` lists package values the page
    also states, each ``(dims, mass)`` in the same units.
    """

    handle: str
    fmt: str
    lang: str
    title: str
    dims: tuple[float, ...]
    dim_unit: str
    mass: float | None
    mass_unit: str
    material: str | None  # catalog word (kb.features.MATERIALS)
    material_text: str | None  # as the page says it
    dim_labels: tuple[str, ...] = ("width", "depth", "height")
    gtin: str | None = None
    package: tuple[tuple[tuple[float, ...], float], ...] = ()
    in_seed: bool = False
    description: str = ""
    updated: str = "Mon, 02 Nov 2026 08:00:00 GMT"
    route: str | None = None  # a path of its own instead of the format's usual one
    extra: dict = field(default_factory=dict, compare=False, hash=False)

    @property
    def path(self) -> str:
        if self.route is not None:
            return self.route
        prefix = {
            "shopify": "/products/",
            "woocommerce": "/shop/product/",
            "amazon": "/dp/",
            "ikea": "/ikea/p/",
        }.get(self.fmt)
        if prefix is not None:
            return prefix + self.handle + ("/" if self.fmt == "woocommerce" else "")
        if self.lang != "en":
            return f"/{self.lang}/p/{self.handle}.html"
        return f"/p/{self.handle}.html"

    @property
    def dims_cm(self) -> tuple[float, ...]:
        """The truth: dimensions in cm, largest first."""
        return tuple(sorted((round(d * _TO_CM[self.dim_unit], 4) for d in self.dims), reverse=True))

    @property
    def mass_g(self) -> float | None:
        return None if self.mass is None else round(self.mass * _TO_G[self.mass_unit], 4)

    @property
    def name(self) -> str:
        """The catalog name the page's title becomes (kb.features.normalize_name)."""
        return " ".join(self.title.lower().split())


def P(
    handle, fmt, lang, title, dims, dim_unit, mass, mass_unit, material, material_text, **kw
) -> DemoProduct:
    return DemoProduct(
        handle, fmt, lang, title, tuple(dims), dim_unit, mass, mass_unit, material, material_text, **kw
    )


# fmt: off
#: The products, in sitemap order. Real objects of their kind; values checked against typical listings.
PRODUCTS: tuple[DemoProduct, ...] = (
    # --- JSON-LD -------------------------------------------------------------------------------------
    P("enamel-tea-kettle", "jsonld", "en", "Enamel Tea Kettle 2 L", (24.0, 21.0, 19.5), "cm", 1100, "g",
      "metal", "enamelled steel", gtin="4006381333931"),
    P("glass-storage-jar", "jsonld", "en", "Glass Storage Jar with Bamboo Lid", (10.4, 10.4, 15.2), "cm", 520, "g",
      "glass", "borosilicate glass", gtin="5012345678900"),
    P("coffee-mug", "jsonld", "en", "Coffee Mug", (12.0, 8.5, 9.5), "cm", 350, "g", "other", "stoneware",
      in_seed=True),
    P("stainless-steel-water-bottle", "jsonld", "en", "Stainless Steel Sports Bottle 750 ml",
      (2.9, 2.9, 10.4), "in", 13.4, "oz", "metal", "18/8 stainless steel",
      dim_labels=("width", "depth", "height")),
    P("cast-iron-skillet", "jsonld_graph", "en", "Cast Iron Skillet 26 cm", (435, 273, 51), "mm", 2.45, "kg",
      "metal", "cast iron", gtin="0075536510206"),
    P("ceramic-salad-bowl", "jsonld_graph", "en", "Ceramic Salad Bowl", (280, 280, 95), "mm", 1.2, "kg",
      "other", "ceramic"),
    P("rolling-pin", "jsonld", "en", "Rolling Pin", (18.0, 2.0, 2.0), "in", 11.2, "oz", "wood", "maple wood",
      dim_labels=("length", "width", "height"), in_seed=True),
    # --- microdata -----------------------------------------------------------------------------------
    P("ceramic-dinner-plate", "microdata", "en", "Porcelain Dinner Plate 27 cm", (27.0, 27.0, 2.5), "cm", 640, "g",
      "other", "porcelain"),
    P("tennis-ball", "microdata", "en", "Tennis Ball", (6.7, 6.7, 6.7), "cm", 58, "g", "fabric", "felt",
      in_seed=True),
    P("bamboo-serving-tray", "microdata", "en", "Bamboo Serving Tray", (40.0, 28.0, 4.5), "cm", 0.85, "kg",
      "wood", "bamboo"),
    # --- Shopify -------------------------------------------------------------------------------------
    P("linen-tea-towel", "shopify", "en", "Linen Tea Towel", (70.0, 50.0, 0.3), "cm", 90, "g", "fabric", "linen"),
    P("soy-wax-candle", "shopify", "en", "Soy Wax Candle in Amber Jar", (8.5, 8.5, 10.0), "cm", 410, "g",
      "other", "soy wax and glass"),
    P("cork-yoga-block", "shopify", "en", "Cork Yoga Block", (23.0, 15.0, 7.5), "cm", 1.5, "lb", "wood",
      "natural cork", dim_labels=("length", "width", "height")),
    P("hand-thrown-planter", "shopify", "en", "Hand-Thrown Terracotta Planter", (14.0, 14.0, 12.5), "cm", 780, "g",
      "other", "terracotta", extra={"grams_zero": True}),
    # --- WooCommerce ---------------------------------------------------------------------------------
    P("oak-chopping-block", "woocommerce", "en", "Oak Chopping Block", (45.0, 30.0, 4.0), "cm", 3.2, "kg",
      "wood", "solid oak", dim_labels=("length", "width", "height")),
    P("felt-laundry-basket", "woocommerce", "en", "Felt Laundry Basket", (40.0, 30.0, 35.0), "cm", 0.65, "kg",
      "fabric", "wool felt", dim_labels=("length", "width", "height")),
    P("stapler", "woocommerce", "en", "Stapler", (15.5, 3.8, 6.2), "cm", 220, "g", "metal", "steel",
      dim_labels=("length", "width", "height"), in_seed=True),
    # --- Amazon-style detail bullets -----------------------------------------------------------------
    P("can-opener", "amazon", "en", "Stainless Steel Can Opener", (8.27, 2.36, 1.57), "in", 7.05, "oz", "metal",
      "stainless steel", dim_labels=("length", "width", "height"), gtin="0810001234567"),
    P("kitchen-scale", "amazon", "en", "Digital Kitchen Scale", (9.25, 6.3, 0.79), "in", 1.06, "lb", "glass",
      "tempered glass", dim_labels=("length", "width", "height"),
      package=(((10.4, 7.5, 1.9), 1.4),)),
    P("cafetera-italiana", "amazon", "es", "Cafetera Italiana de Aluminio 6 Tazas", (16.0, 9.5, 21.5), "cm", 540,
      "g", "metal", "aluminio", dim_labels=("length", "width", "height")),
    # --- IKEA-style product + package lists ----------------------------------------------------------
    P("ikea-desk-lamp", "ikea", "en", "Adjustable Desk Lamp", (14.0, 14.0, 42.0), "cm", 1.1, "kg", "metal",
      "steel, polycarbonate plastic", dim_labels=("width", "depth", "height"),
      package=(((45.0, 15.0, 10.0), 1.3), ((12.0, 7.0, 7.0), 0.05))),
    P("ikea-storage-box", "ikea", "en", "Storage Box with Lid", (35.0, 25.0, 18.0), "cm", 0.6, "kg", "plastic",
      "polypropylene plastic", dim_labels=("length", "width", "height"),
      package=(((36.0, 26.0, 19.0), 0.7),)),
    # --- spec tables in six languages ----------------------------------------------------------------
    P("wasserkocher-edelstahl", "spec_table", "de", "Wasserkocher Edelstahl 1,7 l", (22.5, 16.2, 24.8), "cm",
      1.3, "kg", "metal", "Edelstahl"),
    P("buegeleisen-dampf", "spec_dl", "de", "Dampfbügeleisen 2400 W", (28.0, 12.0, 15.0), "cm", 1.45, "kg",
      "metal", "Edelstahl"),
    P("theiere-fonte", "spec_table", "fr", "Théière en fonte 0,8 L", (18.5, 15.0, 13.0), "cm", 1.15, "kg",
      "metal", "fonte"),
    P("planche-hetre", "spec_dl", "fr", "Planche à découper en hêtre", (40.0, 25.0, 2.0), "cm", 1.1, "kg",
      "wood", "hêtre massif"),
    P("sarten-antiadherente", "spec_table", "es", "Sartén antiadherente 28 cm", (28.0, 49.0, 5.5), "cm", 1.05,
      "kg", "metal", "aluminio forjado"),
    P("jarra-vidrio", "spec_dl", "es", "Jarra de vidrio 1,5 L", (15.5, 11.0, 25.0), "cm", 0.68, "kg", "glass",
      "vidrio borosilicato"),
    P("tagliere-ulivo", "spec_table", "it", "Tagliere in legno d'ulivo", (35.0, 18.0, 2.2), "cm", 0.9, "kg",
      "wood", "legno d'ulivo"),
    P("moka-alluminio", "spec_dl", "it", "Caffettiera moka in alluminio 3 tazze", (13.0, 9.0, 20.0), "cm", 0.45,
      "kg", "metal", "alluminio"),
    P("caneca-ceramica", "spec_table", "pt", "Caneca de cerâmica 350 ml", (12.0, 8.5, 9.5), "cm", 0.32, "kg",
      "other", "cerâmica"),
    P("garrafa-termica", "spec_dl", "pt", "Garrafa térmica 1 L", (9.5, 9.5, 31.0), "cm", 0.52, "kg", "metal",
      "aço inoxidável"),
    P("spec-table-en", "spec_table", "en", "Wooden Cutting Board", (40.0, 30.0, 2.0), "cm", 1.6, "kg", "wood",
      "acacia wood", in_seed=True),
    # --- free text -----------------------------------------------------------------------------------
    P("olive-wood-salad-servers", "free_text", "en", "Olive Wood Salad Servers", (30.0, 6.0, 1.0), "cm", 45, "g",
      "wood", "olive wood", description="Carved from a single piece of olive wood, each server is 30 cm long, "
      "6 cm wide and 1 cm thick, and weighs just 45 g."),
    P("marble-mortar-pestle", "free_text", "en", "Marble Mortar and Pestle", (13.0, 13.0, 8.0), "cm", 1.9, "kg",
      "other", "marble", description="A solid marble mortar, 13 cm across and 8 cm tall; the set weighs 1.9 kg."),
    P("wool-dryer-ball", "free_text", "en", "Wool Dryer Ball", (7.0, 7.0, 7.0), "cm", 40, "g", "fabric",
      "New Zealand wool", description="Each ball measures about 7 x 7 x 7 cm and weighs 40 grams."),
)

# fmt: on


@dataclass(frozen=True)
class BrokenPage:
    """A page that must not become a catalog object; ``expect`` names the reason the run records."""

    path: str
    kind: str
    expect: str
    note: str = ""


#: Pages that a robust crawl must record and skip (listed in the sitemap like the others).
BROKEN_PAGES: tuple[BrokenPage, ...] = (
    BrokenPage(
        "/p/broken-jsonld.html",
        "malformed_jsonld",
        "no_product",
        "the only product data is a JSON-LD block with a syntax error",
    ),
    BrokenPage("/p/server-error.html", "http_500", "http_500", "always answers 500"),
    BrokenPage("/p/slow-teapot.html", "slow", "timeout", "answers after DemoStore.slow_s seconds"),
    BrokenPage("/p/huge-catalogue.html", "huge", "too_large", "a 50 MB page streamed without Content-Length"),
    BrokenPage("/p/giant-mug.html", "absurd", "absurd_value", "a mug 40 m tall"),
    BrokenPage("/about.html", "not_product", "no_product", "the store's about page"),
    BrokenPage("/private/staff-lamp.html", "disallowed", "robots_disallowed", "under a robots.txt Disallow"),
)

#: Extra routes that are not products of their own but lead to one (for de-duplication and redirects).
#: path -> handle of the product they show.
DUPLICATE_ROUTES: dict[str, str] = {
    "/collections/kitchen/products/linen-tea-towel": "linen-tea-towel",  # same page, canonical link
    "/old/cast-iron-pan.html": "cast-iron-skillet",  # 301 to the product page
}

#: A product page that first answers 503 with Retry-After and then the page (exercises retries).
FLAKY_PATH = "/p/flaky-glass-carafe.html"
FLAKY_PRODUCT = P(
    "glass-carafe",
    "jsonld",
    "en",
    "Glass Carafe 1 L",
    (9.0, 9.0, 26.0),
    "cm",
    420,
    "g",
    "glass",
    "borosilicate glass",
    route=FLAKY_PATH,
)


#: The same product sold under another title on another page, with the same GTIN: it must become an alias
#: of the object (and a second source for its values), not a second object.
TWIN_PRODUCTS: tuple[DemoProduct, ...] = (
    P("cast-iron-frying-pan", "jsonld", "en", "Pre-Seasoned Cast Iron Frying Pan", (17.1, 10.75, 2.0), "in",
      5.4, "lb", "metal", "cast iron", gtin="0075536510206", route="/p/pre-seasoned-frying-pan.html"),
)  # fmt: skip


def product_by_handle(handle: str) -> DemoProduct:
    for prod in (*PRODUCTS, FLAKY_PRODUCT, *TWIN_PRODUCTS, *SEARCH_ONLY_PRODUCTS):
        if prod.handle == handle:
            return prod
    raise KeyError(handle)


#: Products the store sells but lists in no sitemap and on no page: only its search finds them (what an
#: on-demand lookup, ``scrapers.lookup``, is for). Two teapots, so a search for "teapot" returns one that
#: does not fit a description of the other.
SEARCH_ONLY_PRODUCTS: tuple[DemoProduct, ...] = (
    P("glazed-ceramic-teapot", "jsonld", "en", "Glazed Ceramic Teapot 1.2 L", (22.0, 15.0, 14.0), "cm", 900, "g",
      "other", "glazed stoneware ceramic", extra={"keywords": "tea pot kettle"}),
    P("cast-iron-teapot", "microdata", "en", "Cast Iron Teapot 0.9 L", (18.5, 15.0, 13.0), "cm", 1.6, "kg",
      "metal", "enamelled cast iron", extra={"keywords": "tea pot tetsubin"}),
    P("copper-mixing-bowl", "spec_table", "en", "Copper Mixing Bowl 30 cm", (30.0, 30.0, 13.0), "cm", 1.1, "kg",
      "metal", "hammered copper", extra={"keywords": "bowl baking"}),
)  # fmt: skip
