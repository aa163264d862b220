"""Objects built from catalog features (sim/objects.py)."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from kb.errors import SimulationError
from kb.features import ObjectRecord
from sim import hand as H
from sim.friction import friction_coefficient
from sim.objects import CONTACT_SOFTNESS, add_object, add_table, object_model


def _obj(**features) -> ObjectRecord:
    base = dict(a_cm=5, b_cm=5, c_cm=5, mass_g=100, shape="compact", material="plastic", texture="medium")
    base.update(features)
    return ObjectRecord.create("thing", **base)


@pytest.mark.parametrize(
    ("features", "kind", "axis"),
    [
        (dict(a_cm=6.5, b_cm=6.5, c_cm=6.5, shape="radial"), "sphere", None),
        (dict(a_cm=26, b_cm=26, c_cm=2, shape="radial"), "cylinder", "c"),  # a plate: a disk
        (dict(a_cm=6, b_cm=4.5, c_cm=4.4, shape="radial"), "ellipsoid", None),  # an egg
        (dict(a_cm=21.5, b_cm=7.2, c_cm=7.2, shape="prism"), "cylinder", "a"),  # a bottle
        (dict(a_cm=19, b_cm=1.0, c_cm=0.9, shape="long"), "cylinder", "a"),  # a pen
        (dict(a_cm=19, b_cm=5, c_cm=1, shape="long"), "box", None),  # a ruler
        (dict(a_cm=15, b_cm=8, c_cm=1.5, shape="thin"), "box", None),
        (dict(a_cm=5, b_cm=5, c_cm=5, shape="compact"), "box", None),
        (dict(a_cm=5, b_cm=5, c_cm=5, shape=None), "box", None),
    ],
)
def test_shape_from_features(features, kind, axis):
    model = object_model(_obj(**features))
    assert model.kind == kind
    assert model.axis_dim == axis


def test_friction_follows_the_shared_table_and_slippery_is_lower():
    glass = object_model(_obj(material="glass", texture="smooth"))
    rubber = object_model(_obj(material="rubber", texture="grippy"))
    assert glass.friction == friction_coefficient("glass", "smooth")
    assert rubber.friction > 2 * glass.friction


def _compiled(obj: ObjectRecord):
    model_obj = object_model(obj)
    spec = mujoco.MjSpec()
    H.configure_options(spec)
    add_table(spec)
    add_object(spec, model_obj, {"a": 0, "b": 1, "c": 2}, [0, 0, 0.05])
    return model_obj, spec.compile()


def test_mass_inertia_priority_and_contact_settings_reach_mujoco():
    model_obj, m = _compiled(_obj(a_cm=10, b_cm=6, c_cm=4, mass_g=250, shape="compact", material="wood"))
    body = m.body("object")
    geom = m.geom("object_geom")
    assert body.mass[0] == pytest.approx(0.25)
    # a solid box: I_xx = m (b^2 + c^2) / 12
    assert body.inertia[0] == pytest.approx(0.25 * (0.06**2 + 0.04**2) / 12, rel=1e-6)
    np.testing.assert_allclose(2 * geom.size, [0.10, 0.06, 0.04])
    assert geom.priority[0] == 1 and geom.condim[0] == 4
    assert geom.friction[0] == pytest.approx(model_obj.friction)
    assert m.opt.cone == mujoco.mjtCone.mjCONE_ELLIPTIC
    assert m.opt.integrator == mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    assert m.opt.impratio == pytest.approx(10.0)


def test_squeezable_objects_have_softer_contacts():
    _, rigid = _compiled(_obj(rigidity="rigid"))
    _, soft = _compiled(_obj(rigidity="squeezable"))
    r, s = rigid.geom("object_geom"), soft.geom("object_geom")
    assert s.solref[0] > r.solref[0]  # slower (softer) contact
    assert s.solimp[2] > r.solimp[2]  # wider impedance ramp: sinks deeper
    assert set(CONTACT_SOFTNESS) == {"rigid", "squeezable", "floppy"}


def test_object_rests_on_the_table():
    _, m = _compiled(_obj(a_cm=8, b_cm=6, c_cm=4, shape="compact"))
    d = mujoco.MjData(m)
    d.qpos[2] = 0.02 + 0.001  # 1 mm above the table top
    mujoco.mj_step(m, d, nstep=250)
    assert d.qpos[2] == pytest.approx(0.02, abs=0.001)
    assert np.all(np.abs(d.qvel) < 0.01)


def test_unknown_features_get_documented_defaults():
    model = object_model(ObjectRecord.create("mystery", mass_g=100))
    assert model.kind == "box"
    assert model.assumptions  # names the assumed size
    assert all(d > 0 for d in model.dims_cm)


def test_object_without_usable_features_is_a_clear_error():
    bogus = ObjectRecord(name="bogus", a_cm=-3.0)  # the plain constructor trusts its input
    with pytest.raises(SimulationError, match="bogus"):
        object_model(bogus)
