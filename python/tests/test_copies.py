"""Input arrays are copied once, into the mesh the library holds, and never on the Python side.

Two checks, each seeing one side:
- C++: the module counts the bytes its one conversion copies (symembed._core._input_bytes_copied);
  a call must add exactly one copy of each array (8 bytes per coordinate, 4 per vertex id).
  This checks that no call converts an array twice; it does not see copies the library may make
  of its own mesh later (the preprocess stage builds the repaired surface it works on).
- numpy: tracemalloc traces numpy's allocations. Arrays of a dtype or memory order the library
  does not store (float32, Fortran order, a strided view of int64 ids) are read in place: the
  call's traced peak stays far below the arrays' size. A conversion made on the Python side, as
  np.ascontiguousarray would make, is seen by the same measure (the control).
"""

import tracemalloc

import numpy as np
import symembed
from symembed import _core

# A plane grid: geodesic distance is Euclidean distance, and the preprocess stage is cheap.
N = 120


def grid():
    """(N*N, 3) float64 vertices of the unit square at z = 0, (2 (N-1)^2, 3) int64 faces."""
    x, y = np.meshgrid(np.linspace(0, 1, N), np.linspace(0, 1, N), indexing="ij")
    V = np.stack([x.ravel(), y.ravel(), np.zeros(N * N)], axis=1)
    i, j = np.meshgrid(np.arange(N - 1), np.arange(N - 1), indexing="ij")
    v = (i * N + j).ravel()
    F = np.concatenate([np.stack([v, v + N, v + N + 1], 1), np.stack([v, v + N + 1, v + 1], 1)])
    return V, F


def one_copy_bytes(V, F):
    return V.size * 8 + F.size * 4


def test_each_input_array_is_copied_once_in_cpp(pair):
    before = _core._input_bytes_copied()
    symembed.match(pair.VA, pair.FA, pair.VB, pair.FB, {"pipeline.sampling.count": 150})
    assert _core._input_bytes_copied() - before == (
        one_copy_bytes(pair.VA, pair.FA) + one_copy_bytes(pair.VB, pair.FB))
    V, F = grid()
    ids = np.arange(10)
    before = _core._input_bytes_copied()
    symembed.geodesic_errors(V, F, np.arange(len(V)), ids, ids)
    assert _core._input_bytes_copied() - before == one_copy_bytes(V, F)


def traced_peak(call):
    """numpy's (and Python's) peak traced allocation during call(), in bytes."""
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        start, _ = tracemalloc.get_traced_memory()
        call()
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    return peak - start


def test_arrays_of_other_layouts_are_not_copied_by_numpy():
    V64, F64 = grid()
    V = np.asfortranarray(V64.astype(np.float32))
    wide = np.zeros((len(F64), 6), dtype=np.int64)
    wide[:, ::2] = F64
    F = wide[:, ::2]  # a strided view
    assert not V.flags.c_contiguous and not F.flags.c_contiguous
    ids = np.arange(len(V))
    smallest = min(V.nbytes, F.nbytes)
    peak = traced_peak(lambda: symembed.geodesic_errors(V, F, ids, ids[:50], ids[:50]))
    assert peak < smallest / 10, (peak, smallest)
    # The control: the copy a conversion to float64 C order makes is seen.
    control = traced_peak(lambda: np.ascontiguousarray(V, dtype=np.float64))
    assert control >= V64.nbytes


def test_the_map_is_returned_without_a_copy(pair, shapes):
    map_ab, result = symembed.match(*shapes)
    assert map_ab.base is not None and not map_ab.flags.owndata  # it holds the C++ vector
    assert result.map is map_ab
