"""symembed.geodesic_errors and symembed.error_curve measure as the binary's evaluation does."""

import json

import numpy as np
import pytest
import symembed
from conftest import PAIR_OPTIONS
from test_copies import N, grid
from symembed.results import read_table


def test_errors_of_the_binary_map_give_its_pair_record(pair):
    errors = symembed.geodesic_errors(pair.VB, pair.FB, pair.cli_map, pair.gt_a, pair.gt_b,
                                      PAIR_OPTIONS)
    assert errors.shape == pair.gt_a.shape
    summary = json.loads((pair.out / "base" / "summary.json").read_text())
    # summary.json's numbers are written with 17 significant digits; the sum's order may differ.
    assert errors.mean() == pytest.approx(summary["mean_direct"], rel=1e-12)
    thresholds, fraction, auc = symembed.error_curve(errors)
    curve = read_table(pair.out / "base" / "curve.csv")
    # curve.csv holds 8 significant digits: rounded by up to 5e-8 of the value (d.ddddddd x 10^e
    # is off by at most 0.5e-7 x 10^e).
    np.testing.assert_allclose(thresholds, curve["threshold"], rtol=5e-8, atol=0)
    np.testing.assert_allclose(fraction, curve["direct"], rtol=5e-8, atol=0)
    assert auc == pytest.approx(summary["auc_direct"], rel=1e-12)


def test_errors_from_a_shape_equal_errors_from_arrays(pair, shapes):
    from_arrays = symembed.geodesic_errors(pair.VB, pair.FB, pair.cli_map, pair.gt_a, pair.gt_b,
                                           PAIR_OPTIONS)
    from_shape = symembed.geodesic_errors(shapes[1], pair.cli_map, pair.gt_a, pair.gt_b)
    np.testing.assert_array_equal(from_shape, from_arrays)


def test_errors_on_a_plane_are_euclidean_distances_over_the_side():
    V, F = grid()  # the unit square: area 1, so errors are distances
    shift = 7
    column = np.arange(len(V)) // N
    row = np.arange(len(V)) % N
    # Each vertex of the left half is mapped `shift` columns further along x.
    movable = np.flatnonzero(column < N - shift)
    map_ab = np.arange(len(V))
    map_ab[movable] = (column[movable] + shift) * N + row[movable]
    lines = movable[:: 97]
    errors = symembed.geodesic_errors(V, F, map_ab, lines, lines)
    # Fast marching on a right-triangle grid is exact along the grid's lines; the evaluator keeps
    # distances as 32-bit floats (relative rounding 6e-8).
    np.testing.assert_allclose(errors, shift / (N - 1), rtol=1e-6)


def test_errors_refuse_ids_outside_the_mesh(pair):
    with pytest.raises(symembed.InvalidInputError, match="out of range"):
        symembed.geodesic_errors(pair.VB, pair.FB, pair.cli_map, pair.gt_a, pair.gt_b + len(pair.VB))
    with pytest.raises(symembed.InvalidInputError, match="differ in length"):
        symembed.geodesic_errors(pair.VB, pair.FB, pair.cli_map, pair.gt_a, pair.gt_b[:-1])


def test_the_curve_counts_errors_at_most_each_threshold():
    thresholds, fraction, auc = symembed.error_curve([0.0, 0.1, 0.3], max_error=0.2, step=0.1)
    np.testing.assert_allclose(thresholds, [0.0, 0.1, 0.2])
    np.testing.assert_allclose(fraction, [1 / 3, 2 / 3, 2 / 3])
    # Trapezoids over [0, 0.2], divided by 0.2.
    assert auc == pytest.approx((0.5 * (1 / 3 + 2 / 3) + 0.5 * (2 / 3 + 2 / 3)) / 2)
