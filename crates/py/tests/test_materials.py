"""bwc.materials: a law from materials and geometry, against the contact mechanics written out
here, and its Thornton law used as a contact element whose host rebounds at the predicted CoR."""

import math
import pathlib

import pytest

import bwc
from hosts import rebound

FIXTURE = pathlib.Path(__file__).resolve().parents[3] / "fixtures" / "alumina_on_aluminium.toml"
SPHERE = {"material": "alumina", "radius": 2.5e-3}
PLATE = {"material": "aluminium-6061-t6"}


def test_the_law_from_materials_is_hertz_and_thornton():
    law = bwc.materials({"materials": {"body1": SPHERE, "body2": PLATE, "v0": [0.5, 2.0]}})
    e_star = 1 / ((1 - 0.22 ** 2) / 370e9 + (1 - 0.33 ** 2) / 68.9e9)
    d = law.derived
    assert math.isclose(d.E_star, e_star, rel_tol=1e-14)
    assert math.isclose(d.k, 4 / 3 * e_star * math.sqrt(2.5e-3), rel_tol=1e-14)
    p_y = 1.295 * math.exp(0.736 * 0.33) * 276e6
    assert math.isclose(d.p_y, p_y, rel_tol=1e-14) and d.yields_first == 2
    m = 4 / 3 * math.pi * 2.5e-3 ** 3 * 3890
    # Thornton's sphere-on-flat yield speed, 1.56 (p_y^5 / (E*^4 rho))^(1/2), to his 3 digits.
    assert math.isclose(d.v_y, 1.56 * math.sqrt(p_y ** 5 / (e_star ** 4 * 3890)), rel_tol=5e-4)
    assert math.isclose(d.m_star, m, rel_tol=1e-14)
    assert law.units.v_y == "m/s" and law.units.k == "N/m^(3/2)"
    assert [row.v0 for row in law.cor] == [0.5, 2.0]


def test_the_jackson_green_element_from_materials_rebounds_at_the_tabulated_cor():
    """The table's Jackson-Green CoR comes from a chain run (a body against a wall); the
    element driven by a host here is another integration of the same law."""
    law = bwc.materials({"materials": {"body1": SPHERE, "body2": PLATE, "v0": [1.0]}})
    element = dict(law.laws.jackson_green.element)
    contact = bwc.Contact(element.pop("law"), element)
    v_out = rebound(contact, law.derived.m_star, 1.0, 1e-8)
    row = law.cor[0]
    assert abs(v_out - row.e_jackson_green) < 1e-6, (v_out, row.e_jackson_green)
    assert row.e < row.e_jackson_green < 1.0


def test_the_thornton_element_from_materials_rebounds_at_the_tabulated_cor():
    law = bwc.materials({"materials": {"body1": SPHERE, "body2": PLATE, "v0": [1.0]}})
    element = law.laws.thornton.element
    contact = bwc.Contact(element.law, {"k": element.k, "delta_y": element.delta_y})
    v_out = rebound(contact, law.derived.m_star, 1.0, 1e-8)
    assert abs(v_out - law.cor[0].e) < 1e-6, (v_out, law.cor[0].e)


def test_bad_materials_are_named():
    with pytest.raises(bwc.BwcError, match='"alumna" is not a known material: steel-aisi-52100'):
        bwc.materials({"materials": {"body1": {**SPHERE, "material": "alumna"}, "body2": PLATE}})
    with pytest.raises(bwc.BwcError, match="poisson.*-1 < nu < 0.5"):
        bwc.materials({"materials": {"body1": SPHERE, "body2": {**PLATE, "poisson": 0.6}}})


def test_a_bouc_wen_law_fitted_to_the_law_from_materials(tmp_path):
    law = bwc.materials(FIXTURE, fit=tmp_path)
    shccm = law.fits[0]
    assert shccm.model == "shccm" and shccm.e_error < 0.01 and shccm.t_d_error < 0.01
    assert math.isclose(shccm.SI.m, law.derived.m_star, rel_tol=1e-12)
    assert (tmp_path / "reference.csv").exists() and (tmp_path / "fit.toml").exists()
    assert [f.model for f in law.loop_fits] == ["shccm", "mcm"]
    assert law.loop_fits[0].F_max_error < 0.1
    # Its SI law simulated by bwc.cor rebounds within the fit's error of Thornton's table.
    si = {key: shccm.SI[key] for key in ["m", "k", "c", "n", "p", "alpha", "beta", "gamma", "A"]}
    row = law.cor[6]
    e = float(bwc.cor("shccm", si, row.v0).e)
    assert abs(e - row.e) <= shccm.e_error + 1e-9, (e, row.e)
