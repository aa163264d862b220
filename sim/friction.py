"""Friction between a fingertip pad and an object, from the object's material and texture.

One table shared by the grasp planner (sim/planner.py: the grip force needed) and the simulator (the
object's geom friction in MuJoCo), so that what the planner assumes is what the physics uses.

Coefficients are dry sliding friction of a soft, skin-like fingertip pad against the material, rounded
engineering values inside the ranges reported for human skin on everyday materials (Derler & Gerhardt,
"Tribology of skin: review and analysis of experimental results for the friction coefficient of human
skin", Tribology Letters 45, 2012: about 0.2 to 1.0+ for dry skin; rubber and soft polymers at the top,
glass, metal and hard plastics lower, fabric and paper in between). Texture scales the material value:
a smooth finish (glossy glass, polished metal) loses grip, a textured or rubberised one gains it.

The values are deliberately conservative (a little low): a planner that underestimates friction squeezes
a little harder, which is safer than dropping the object.
"""

from __future__ import annotations

__all__ = [
    "DEFAULT_FRICTION",
    "MATERIAL_FRICTION",
    "MAX_FRICTION",
    "MIN_FRICTION",
    "TEXTURE_FACTOR",
    "friction_coefficient",
]

#: Sliding friction of a fingertip pad on each material (medium texture). Keys are kb.features.MATERIALS.
MATERIAL_FRICTION: dict[str, float] = {
    "fabric": 0.6,  # cloth, felt (tennis ball): fibres interlock with the pad
    "glass": 0.4,  # hard and smooth; dry skin on glass is about 0.3-0.9, take the low side
    "metal": 0.4,  # steel, aluminium: similar to glass when dry
    "paper": 0.5,  # paper and cardboard
    "plastic": 0.45,  # hard plastics (ABS, PP, PE): slightly above glass
    "rubber": 0.9,  # rubber, silicone: the grippiest household material
    "wood": 0.5,  # unfinished to varnished wood
    "other": 0.45,  # ceramics, stone, foam, unknown mixes: like hard plastic
}

#: Multiplier on the material value for each texture. Keys are kb.features.TEXTURES.
TEXTURE_FACTOR: dict[str, float] = {
    "smooth": 0.8,  # glossy, polished
    "medium": 1.0,
    "rough": 1.15,  # ridged, knurled, fibrous
    "grippy": 1.4,  # rubberised or soft-touch surfaces made to be held
}

#: Used when material is unknown (texture still applies): hard plastic, the commonest material.
DEFAULT_FRICTION = MATERIAL_FRICTION["plastic"]
#: Bounds on the result: below 0.2 nothing household-like is that slippery when dry; above 1.5 MuJoCo
#: contacts with elliptic cones get stiff and gain nothing for holding.
MIN_FRICTION = 0.2
MAX_FRICTION = 1.5


def friction_coefficient(material: str | None, texture: str | None) -> float:
    """Sliding friction coefficient of a fingertip on an object of ``material`` with ``texture``.

    Unknown (None) material counts as :data:`DEFAULT_FRICTION`, unknown texture as medium; words not in
    the tables raise ``KeyError`` (values are expected to be canonical, see ``kb.features``).
    """
    base = DEFAULT_FRICTION if material is None else MATERIAL_FRICTION[material]
    factor = 1.0 if texture is None else TEXTURE_FACTOR[texture]
    return round(min(MAX_FRICTION, max(MIN_FRICTION, base * factor)), 4)
