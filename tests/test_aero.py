"""The aerodynamic models: which have the quadratic form, and that the coefficients agree."""

import math

import numpy as np
import pytest

from mcrun.physics import aero

# ferguson2022 (as published), penner2002 (tuned to Penner 2002) and trackman2019 (refitted)
# share C_D = a0 + a1 S + a2 S^2, C_L = b0 + b1 S + b2 S^2; smits_smith1994 and lyu2018 have
# forms of their own.
QUADRATIC = {"ferguson2022", "penner2002", "trackman2019"}


@pytest.mark.parametrize("name", aero.MODELS)
def test_every_model_is_classified_as_intended(name):
    model = aero.MODELS[name]
    quadratic = name in QUADRATIC
    assert aero.is_quadratic(model) == quadratic
    assert np.isfinite(aero.QUADRATIC_COEFFICIENTS[model]).all() == quadratic


@pytest.mark.parametrize("name", aero.MODELS)
def test_coefficients_follow_the_classification(name):
    """A quadratic model's coefficients are the quadratic of its row; the others are finite
    without one (their rows are NaN)."""
    model = aero.MODELS[name]
    table = aero.QUADRATIC_COEFFICIENTS
    for spin_ratio, reynolds in ((0.05, 1.8e5), (0.2, 1.2e5), (0.9, 6.0e4)):
        cd, cl = aero.coefficients(model, spin_ratio, reynolds, table)
        assert math.isfinite(cd) and math.isfinite(cl)
        if aero.is_quadratic(model):
            assert (cd, cl) == aero.quadratic(spin_ratio, *table[model])


def test_a_model_not_listed_is_not_quadratic():
    """The quadratic lanes take the models listed, not every model but the others: the id a new
    model would have is not quadratic until it is listed."""
    assert not aero.is_quadratic(len(aero.MODELS))
    assert set(aero.QUADRATIC_MODELS) == {aero.MODELS[name] for name in QUADRATIC}
