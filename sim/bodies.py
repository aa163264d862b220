"""The shape of a simulated object: one primitive, or a composite of a few (a mug's cylinder and handle).

:func:`body_for` turns an object's (resolved) sizes, shape and name into a :class:`Body`: a tuple of
:class:`Part` primitives laid out in the object's own frame, whose axes are the catalog dimensions a, b, c
and whose origin is the centre of the stated a x b x c box. sim/objects.py adds the parts to MuJoCo;
sim/world.py poses the body on the table. The mapping (sim/PHYSICS.md, "Object geometry"):

* **Vessels with a handle** (mug, teacup, pitcher, jug, teapot, kettle, moka pot, coffee pot, French
  press): an upright cylinder plus a loop handle (two struts and a grip bar, boxes) on one side; teapots
  and kettles also get a spout (a capsule) on the other. Open vessels (cups, jugs) show a dark opening on
  top (a visual disk without mass or contacts).
* **Pans** (frying pan, skillet, saucepan, wok) **and ladles** (a bowl on a long handle): a thin base disk,
  a wall ring of boxes and a long handle along ``a`` at the rim's height.
* **Peaked caps** (baseball cap, ball cap, peaked cap: :data:`PEAKED_NOUNS`): a crown of three stacked
  cylinders narrowing to the top, and a brim (a thin box) at its base reaching out along ``a``.
* **Round objects** (cans, bottles, jars, cups, glasses, plates, bowls, coins, rolls, candles, ...; and any
  prism or long object whose two smaller sides are within 20 %): a cylinder along the odd dimension
  (along ``a`` when ``b`` ~ ``c``: a bottle, a pen; along ``c`` when ``a`` ~ ``b`` and the shape is not
  prism: a tuna can, a plate, a coin; a prism can with ``a`` ~ ``b`` is a square tin).
* **Radial** objects: a sphere (all sides within 20 %), a disk (two larger sides within 20 %) or an
  ellipsoid. **Boxes, cartons, blocks, bricks, books, boards** stay boxes whatever their ratios; so do
  thin, compact and other objects.

Mass: the catalog's total, spread over the parts by volume (one uniform density; MuJoCo computes each
part's inertia from its share). Sizes: every body fits the stated box and touches its faces, so a, b and c
are the body's extents; when a vessel's stated sizes leave no room for its handle (a pitcher 23.5 x 10.8 x
10.8 cm: measured without it), the handle is added outside them and an assumption says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from kb.kinds import noun_in, words_of

__all__ = [
    "GEOMETRY_VERSION",
    "Body",
    "Handle",
    "Part",
    "ROUND_RATIO",
    "body_for",
    "handle_style",
    "peaked",
]

#: Part of the hand version stored with every trial (sim/hand.py): bump it when a body changes, so that
#: stored validations are re-run. 2: composite bodies from the kind (1: one primitive from the shape); 3: floppy
#: flat objects drape as hinged strips (sim/sheet.py); 4: a flat object too narrow to overhang a table edge
#: under the pads lies with its length across it (sim/grasps.py edge_depth_cm); 5: a ladle is a bowl on a long
#: handle (HANDLE_NOUNS), not a uniform box; 6: a peaked cap is a crown on a brim (PEAKED_NOUNS).
GEOMETRY_VERSION = "6"
#: Sides within this ratio count as equal (a sphere, a disk, a round cross-section).
ROUND_RATIO = 0.8
#: Objects named with one of these words are round in cross-section when two of their sides are about
#: equal, whatever their catalog shape ("compact" tuna can, "thin" plate, coin).
ROUND_WORDS = frozenset(
    "can tin jar cup mug glass tumbler bottle flask thermos vase coin quarter disk disc cylinder roll "
    "tealight candle cap puck plate saucer coaster bowl battery pot pan lid".split()
)
#: ... and these are boxes, whatever their ratios (a milk carton, a wood block, a book).
SQUARE_WORDS = frozenset("box carton block brick cube book board card case crate".split())
#: English head nouns (kb/data/kind_nouns.csv) of objects with a handle, and its style: ``loop`` beside an
#: upright vessel (plus a spout for ``spout``), ``long`` along a pan's length.
HANDLE_NOUNS: dict[str, str] = {
    "mug": "loop",
    "teacup": "loop",
    "measuring cup": "loop",
    "pitcher": "loop",
    "jug": "loop",
    "moka pot": "loop",
    "french press": "loop",
    "teapot": "spout",
    "kettle": "spout",
    "electric kettle": "spout",
    "coffee pot": "spout",
    "frying pan": "long",
    "pan": "long",
    "skillet": "long",
    "saucepan": "long",
    "wok": "long",
    "ladle": "long",  # a bowl on a long handle: built as a small pan, its mass by volume at the bowl end
}
#: English head nouns of peaked caps: a crown (a stepped dome of three cylinders) on a brim (a thin plate)
#: reaching out along ``a`` (:func:`_peaked_cap`).
PEAKED_NOUNS = frozenset({"baseball cap"})
#: The crown's tiers: (fraction of the height, fraction of the crown's radius), bottom to top.
CAP_TIERS = ((5 / 12, 1.0), (4 / 12, 0.8), (3 / 12, 0.5))
#: ``GraspPlan.params["hold"]`` for a grasp of one named part of a composite body (``params["part"]``:
#: a cap's ``crown_top`` from above, its ``brim`` pinched at a table edge; sim/world.py places the hand).
HOLD_PART = "part"
#: ``GraspPlan.params["hold"]`` for a grasp of the object's handle rather than its body (sim/world.py places
#: the hand on it; the planner asks for it for a pan, sim/planner.py).
HOLD_HANDLE = "handle"
#: ``GraspPlan.params["handle_grip"]``: where along a long handle the palm's middle goes.
HANDLE_GRIPS = ("end", "middle")
#: Open vessels show their opening (a dark disk on top); the others have a lid.
OPEN_VESSELS = frozenset({"mug", "teacup", "measuring cup", "pitcher", "jug"})
#: A loop handle reaches out this fraction of the vessel's diameter when the stated sizes leave no room.
LOOP_REACH = 0.4
#: A handle needs at least this fraction of the diameter beyond the body to fit inside the stated sizes.
MIN_HANDLE_ROOM = 0.15
#: A pan's handle is added outside its stated sizes when ``a - b`` is shorter than this fraction of ``b``.
MIN_PAN_HANDLE = 0.25
PAN_WALL_SEGMENTS = 16
_DIMS = "abc"


@dataclass(frozen=True)
class Part:
    """One MuJoCo primitive of a body, in the object's frame (axes a, b, c; cm; origin the box centre).

    ``geom``: box, cylinder, capsule, sphere or ellipsoid. ``size_cm``: MuJoCo's half-sizes: a box's or an
    ellipsoid's half-extents along a, b, c; a cylinder's or capsule's (radius, half-length, 0); a
    sphere's (radius, 0, 0). ``axis``: a cylinder's or capsule's direction (unit vector in a, b, c).
    ``turn_deg``: a box turned by this angle about ``axis`` (a pan's wall segments). ``collides``: False for
    a visual part (no mass, no contacts). ``mass_kg`` is filled in by :func:`body_for`.
    """

    name: str
    geom: str
    size_cm: tuple[float, float, float]
    pos_cm: tuple[float, float, float] = (0.0, 0.0, 0.0)
    axis: tuple[float, float, float] = (0.0, 0.0, 1.0)
    turn_deg: float = 0.0
    collides: bool = True
    mass_kg: float = 0.0
    rgba: tuple[float, float, float, float] | None = None  # None: the object's material colour

    def extent_cm(self, dim: str) -> float:
        """The part's extent along catalog dimension ``dim`` (for parts along a dimension, unturned)."""
        i = _DIMS.index(dim)
        x, y, z = self.size_cm
        if self.geom == "sphere":
            return 2.0 * x
        if self.geom in ("cylinder", "capsule"):
            along = abs(self.axis[i]) > 0.5
            return 2.0 * (y + (x if self.geom == "capsule" else 0.0)) if along else 2.0 * x
        return 2.0 * self.size_cm[i]

    @property
    def volume_cm3(self) -> float:
        """The volume MuJoCo gives this primitive (0 for a visual part)."""
        if not self.collides:
            return 0.0
        x, y, z = self.size_cm
        if self.geom == "box":
            return 8.0 * x * y * z
        if self.geom == "cylinder":
            return math.pi * x * x * 2.0 * y
        if self.geom == "capsule":
            return math.pi * x * x * 2.0 * y + 4.0 / 3.0 * math.pi * x**3
        if self.geom == "sphere":
            return 4.0 / 3.0 * math.pi * x**3
        return 4.0 / 3.0 * math.pi * x * y * z  # ellipsoid


@dataclass(frozen=True)
class Handle:
    """A body's handle: ``style`` loop or long; ``dim``: the catalog dimension it reaches out along (on the
    + side of the object's frame); ``width_cm``/``thickness_cm``: the cross-section of where it is held;
    ``length_cm``: how far it reaches beyond the body; ``inside``: within the stated sizes."""

    style: str
    dim: str
    width_cm: float
    thickness_cm: float
    length_cm: float
    inside: bool = True


@dataclass(frozen=True)
class Body:
    """What an object is built of. ``form``: box, cylinder, sphere, ellipsoid, vessel or pan; ``up``: the
    dimension that stands up when the object stands as it is used (a vessel's height, a pan's depth), else
    None; ``round_dims``: the two dimensions across a plain cylinder (its diameter is their mean)."""

    form: str
    parts: tuple[Part, ...]
    up: str | None = None
    handle: Handle | None = None
    round_dims: tuple[str, ...] = ()
    assumptions: tuple[str, ...] = field(default=())

    @property
    def main(self) -> Part:
        return self.parts[0]


def _unit(dim: str) -> tuple[float, float, float]:
    return tuple(1.0 if d == dim else 0.0 for d in _DIMS)  # type: ignore[return-value]


def _vec(**by_dim: float) -> tuple[float, float, float]:
    return tuple(float(by_dim.get(d, 0.0)) for d in _DIMS)  # type: ignore[return-value]


def _clamp(x: float, lo: float, hi: float) -> float:
    return max(lo, min(hi, x))


def handle_style(name: str | None, aliases: tuple[str, ...] = ()) -> tuple[str, str] | None:
    """(style, English noun) of an object with a handle, from the head noun of its name or aliases."""
    for phrase in (name or "", *aliases):
        words = words_of(phrase)
        noun = noun_in(words) or noun_in(words, head_last=False)  # a store title in another language
        if noun is None:
            continue
        for key in (noun.english, noun.text):
            if key in HANDLE_NOUNS:
                return HANDLE_NOUNS[key], key
        return None  # the name's own noun decides; an alias is only asked when the name has none
    return None


def _words(name: str | None, aliases: tuple[str, ...]) -> set[str]:
    """The words of the name and first alias, plus their head nouns' English names ("caffettiera" ->
    moka, pot)."""
    out = set(words_of(name or ""))
    for phrase in (name or "", *aliases[:1]):
        noun = noun_in(words_of(phrase))
        if noun is not None:
            out.update(words_of(noun.english))
    return out


def _single(sizes: dict[str, float], shape: str, words: set[str]) -> Body:
    """One primitive (see the module docstring)."""
    a, b, c = sizes["a"], sizes["b"], sizes["c"]
    half = _vec(a=a / 2, b=b / 2, c=c / 2)
    round_word, square_word = bool(words & ROUND_WORDS), bool(words & SQUARE_WORDS)
    if shape == "radial" and not square_word:
        if c >= ROUND_RATIO * a:
            return Body("sphere", (Part("body", "sphere", ((a + b + c) / 6.0, 0.0, 0.0)),))
        if b >= ROUND_RATIO * a:
            return _cylinder("c", sizes)
        return Body("ellipsoid", (Part("body", "ellipsoid", half),))
    if not square_word:
        if (shape in ("prism", "long") or round_word) and c >= ROUND_RATIO * b:
            return _cylinder("a", sizes)
        if round_word and shape != "prism" and b >= ROUND_RATIO * a:  # a prism is square: a spam can
            return _cylinder("c", sizes)
    return Body("box", (Part("body", "box", half),))


def _cylinder(axis: str, sizes: dict[str, float]) -> Body:
    across = tuple(d for d in _DIMS if d != axis)
    radius = sum(sizes[d] for d in across) / 4.0
    part = Part("body", "cylinder", (radius, sizes[axis] / 2.0, 0.0), axis=_unit(axis))
    return Body("cylinder", (part,), round_dims=across)


def _vessel_layout(sizes: dict[str, float]) -> tuple[str, str, str, bool]:
    """(height, handle, diameter) dimensions of an upright vessel, and whether the handle fits inside the
    stated sizes. The diameter is the smallest side; of the other two, the handle reaches out along the
    one whose excess over the diameter is nearest a typical handle's (LOOP_REACH of the diameter)."""
    d = "c"
    options = [("a", "b"), ("b", "a")]  # (height, handle)
    h, e = min(options, key=lambda he: abs((sizes[he[1]] - sizes[d]) / sizes[d] - LOOP_REACH))
    if sizes[e] - sizes[d] < MIN_HANDLE_ROOM * sizes[d]:  # neither leaves room: the larger is the height
        h, e = "a", "b"
        return h, e, d, False
    return h, e, d, True


def _vessel(sizes: dict[str, float], style: str, noun: str) -> Body:
    h, e, d, inside = _vessel_layout(sizes)
    dia, height = sizes[d], sizes[h]
    span = sizes[e] - dia if inside else LOOP_REACH * dia  # beyond the body, handle and spout together
    spout = 0.45 * span if style == "spout" else 0.0
    reach = span - spout
    lo = -sizes[e] / 2.0  # the body's far side (the spout's side)
    centre = (lo + spout + dia / 2.0) if inside else 0.0
    parts = [Part("body", "cylinder", (dia / 2.0, height / 2.0, 0.0), pos_cm=_vec(**{e: centre}), axis=_unit(h))]
    bar = _clamp(0.12 * dia, 0.8, 1.5)  # the grip bar's thickness (along the handle's reach)
    width = _clamp(0.18 * dia, 1.2, 2.5)  # across it
    grip = 0.6 * height
    wall = centre + dia / 2.0
    bar_at = wall + reach - bar / 2.0
    parts.append(Part("handle_grip", "box", _vec(**{e: bar / 2, d: width / 2, h: grip / 2}), _vec(**{e: bar_at})))
    strut_len = reach - bar + 0.6  # 6 mm into the wall
    for name, z in (("handle_top", grip / 2 - bar / 2), ("handle_bottom", -grip / 2 + bar / 2)):
        pos = _vec(**{e: wall - 0.6 + strut_len / 2, h: z})
        parts.append(Part(name, "box", _vec(**{e: strut_len / 2, d: width / 2, h: bar / 2}), pos))
    if spout:  # a capsule rising at 40 degrees from inside the wall to the stated side (its tip included)
        radius = _clamp(0.07 * dia, 0.5, 1.2)
        tilt = math.radians(40.0)
        start = (centre - dia / 2.0 + 0.5, -0.1 * height)
        run = start[0] - (lo + radius)
        end = (lo + radius, start[1] + run * math.tan(tilt))
        length = math.hypot(run, end[1] - start[1])
        mid = _vec(**{e: (start[0] + end[0]) / 2.0, h: (start[1] + end[1]) / 2.0})
        axis = _vec(**{e: -math.cos(tilt), h: math.sin(tilt)})
        parts.append(Part("spout", "capsule", (radius, length / 2.0, 0.0), mid, axis))
    if noun in OPEN_VESSELS:
        top = _vec(**{e: centre, h: height / 2.0 + 0.02})
        parts.append(Part("opening", "cylinder", (0.43 * dia, 0.02, 0.0), top, _unit(h), collides=False,
                          rgba=(0.08, 0.06, 0.05, 1.0)))  # fmt: skip
    handle = Handle("loop", e, width, bar, reach, inside)
    notes = () if inside else (
        f"handle added outside the stated sizes (they leave no room for it): reaches {reach:.1f} cm beyond",
    )  # fmt: skip
    return Body("vessel", tuple(parts), up=h, handle=handle, assumptions=notes)


def _pan(sizes: dict[str, float]) -> Body:
    """A pan lying as it is used: depth ``c`` up, the body round across ``b``, the handle along ``a``."""
    a, b, c = sizes["a"], sizes["b"], sizes["c"]
    inside = a - b >= MIN_PAN_HANDLE * b
    length = a - b if inside else 0.6 * b
    centre = -a / 2.0 + b / 2.0 if inside else 0.0
    base_t = _clamp(0.15 * c, 0.3, 1.0)
    wall_t = _clamp(0.1 * c, 0.3, 0.6)
    parts = [Part("body", "cylinder", (b / 2.0, base_t / 2.0, 0.0), _vec(a=centre, c=-c / 2 + base_t / 2), _unit("c"))]
    n = PAN_WALL_SEGMENTS  # the sides of a polygon inscribed in the rim: its corners on the stated circle
    seg = b * math.sin(math.pi / n)
    wall_h = c - base_t
    r = b / 2.0 * math.cos(math.pi / n) - wall_t / 2.0
    for k in range(n):
        t = 2.0 * math.pi * k / n
        pos = _vec(a=centre + r * math.cos(t), b=r * math.sin(t), c=-c / 2 + base_t + wall_h / 2)
        parts.append(Part(f"wall_{k}", "box", _vec(a=wall_t / 2, b=seg / 2, c=wall_h / 2), pos, _unit("c"),
                          turn_deg=math.degrees(t)))  # fmt: skip
    width = _clamp(0.1 * b, 2.0, 3.5)
    thick = _clamp(0.4 * c, 1.0, 2.5)
    rim = centre + b / 2.0 - wall_t
    pos = _vec(a=rim + (length + wall_t) / 2.0, c=c / 2.0 - thick / 2.0)
    parts.append(Part("handle_grip", "box", _vec(a=(length + wall_t) / 2.0, b=width / 2.0, c=thick / 2.0), pos))
    notes = () if inside else (f"handle added outside the stated sizes: {length:.1f} cm long",)
    return Body("pan", tuple(parts), up="c", handle=Handle("long", "a", width, thick, length, inside),
                assumptions=notes)  # fmt: skip


def peaked(name: str | None, aliases: tuple[str, ...] = ()) -> bool:
    """Is the object a peaked cap (its name's head noun, else its first alias's, in :data:`PEAKED_NOUNS`)?"""
    for phrase in (name or "", *aliases[:1]):
        noun = noun_in(words_of(phrase))
        if noun is not None:
            return noun.english in PEAKED_NOUNS or noun.text in PEAKED_NOUNS
    return False


def _peaked_cap(sizes: dict[str, float]) -> Body:
    """A cap resting on its crown as it lies on a table: the crown round across ``b`` (its diameter), ``c``
    up, three stacked cylinders narrowing to the top (a stepped dome, :data:`CAP_TIERS`); the brim a thin
    plate at the crown's base reaching out along ``+a`` by ``a - b``, 0.9 of the crown's width."""
    a, b, c = sizes["a"], sizes["b"], sizes["c"]
    notes: list[str] = []
    brim_len = a - b
    if brim_len < 0.25 * b:  # the stated sizes leave no brim: one of 0.4 of the crown added outside
        brim_len = 0.4 * b
        notes.append(f"brim added outside the stated sizes: {brim_len:.1f} cm")
    crown_r = b / 2.0
    centre = -a / 2.0 + crown_r if a - b >= 0.25 * b else 0.0
    parts, z = [], -c / 2.0
    for k, (h_frac, r_frac) in enumerate(CAP_TIERS):
        h = h_frac * c
        name = "crown_top" if k == len(CAP_TIERS) - 1 else f"crown_{k}"
        parts.append(Part(name, "cylinder", (r_frac * crown_r, h / 2.0, 0.0), _vec(a=centre, c=z + h / 2.0), _unit("c")))
        z += h
    thick = _clamp(0.02 * b, 0.3, 0.5)
    half = _vec(a=brim_len / 2.0, b=0.45 * b, c=thick / 2.0)
    parts.append(Part("brim", "box", half, _vec(a=centre + crown_r + brim_len / 2.0, c=-c / 2.0 + thick / 2.0)))
    return Body("cap", tuple(parts), up="c", assumptions=tuple(notes))


def body_for(
    sizes_cm: tuple[float, float, float],
    shape: str,
    mass_kg: float,
    *,
    name: str | None = None,
    aliases: tuple[str, ...] = (),
) -> Body:
    """The body of an object with sorted sizes ``sizes_cm`` (a >= b >= c, all known: the planner's
    resolved ones), catalog ``shape`` and total ``mass_kg``; its name and aliases give its kind."""
    sizes = dict(zip(_DIMS, (float(s) for s in sizes_cm), strict=True))
    style = handle_style(name, aliases)
    if peaked(name, aliases):
        body = _peaked_cap(sizes)
    elif style is not None and style[0] == "long":
        body = _pan(sizes)
    elif style is not None and style[0] in ("loop", "spout"):
        body = _vessel(sizes, *style)
    else:
        body = _single(sizes, shape, _words(name, aliases))
    total = sum(p.volume_cm3 for p in body.parts)
    parts = tuple(
        Part(**{**p.__dict__, "mass_kg": mass_kg * p.volume_cm3 / total if p.collides else 0.0}) for p in body.parts
    )
    return Body(body.form, parts, body.up, body.handle, body.round_dims, body.assumptions)
