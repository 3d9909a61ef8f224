"""symembed.match and symembed.Shape give the binary's map, bit for bit."""

import numpy as np
import symembed
from conftest import PAIR_OPTIONS


def test_match_from_arrays_equals_the_binary_map(pair):
    map_ab, result = symembed.match(pair.VA, pair.FA, pair.VB, pair.FB, PAIR_OPTIONS)
    assert map_ab.dtype == np.int32 and map_ab.shape == (len(pair.VA),)
    np.testing.assert_array_equal(map_ab, pair.cli_map)
    assert result.map is map_ab


def test_match_with_the_defaults_equals_the_binary_map_with_the_defaults(pair):
    map_ab, _ = symembed.match(pair.VA, pair.FA, pair.VB, pair.FB)
    np.testing.assert_array_equal(map_ab, pair.cli_map_defaults)


def test_match_with_the_config_file_equals_the_binary_map(pair):
    map_ab, _ = symembed.match(pair.VA, pair.FA, pair.VB, pair.FB, config=pair.config)
    np.testing.assert_array_equal(map_ab, pair.cli_map)


def test_match_of_shapes_equals_the_binary_map(pair, shapes):
    a, b = shapes
    map_ab, result = symembed.match(a, b)
    np.testing.assert_array_equal(map_ab, pair.cli_map)
    assert result.source is a and result.target is b


def test_result_describes_the_pair(pair, shapes):
    _, result = symembed.match(*shapes)
    assert result.candidates.shape == (4, 3, 3)
    assert 0 <= result.chosen < 4
    np.testing.assert_array_equal(result.rotation, result.candidates[result.chosen])
    assert result.scores.shape == (4,)
    assert set(result.stages) >= {"flip", "matching", "refine"}
    for stage in ("flip", "matching", "refine"):
        entry = result.stages[stage]
        assert entry["seconds"] >= 0 and isinstance(entry["converged"], bool)
        assert isinstance(entry["message"], str)


def test_shape_holds_its_arrays_and_stage_outputs(pair, shapes):
    a, _ = shapes
    np.testing.assert_array_equal(a.vertices, pair.VA)
    np.testing.assert_array_equal(a.faces, pair.FA)
    assert not a.vertices.flags.writeable
    names = [s["stage"] for s in a.stages]
    assert names[:3] == ["load", "preprocess", "sampling"]
    assert len(a.samples) == PAIR_OPTIONS["pipeline.sampling.count"]
    V, F = a.surface
    assert a.embedding.shape == (len(V), 3) and F.shape[1] == 3
    assert "count: 150" in a.config


def test_arrays_of_any_dtype_and_order_are_read_alike(pair):
    V = np.asfortranarray(pair.VA)
    F = pair.FA.astype(np.uint32)
    shape = symembed.Shape(V, F, PAIR_OPTIONS)
    np.testing.assert_array_equal(shape.vertices, pair.VA)
    np.testing.assert_array_equal(shape.faces, pair.FA)
    reference = symembed.Shape(pair.VA, pair.FA, PAIR_OPTIONS)
    np.testing.assert_array_equal(shape.embedding, reference.embedding)


def test_shapes_computed_with_different_options_are_not_matched(pair, shapes):
    other = symembed.Shape(pair.VB, pair.FB, {"pipeline.sampling.count": 120})
    try:
        symembed.match(shapes[0], other)
    except symembed.ConfigError as e:
        assert "different stage options" in str(e)
    else:
        raise AssertionError("matched shapes of two pipelines")


def test_the_cache_serves_a_shape_computed_before(pair, tmp_path):
    first = symembed.Shape(pair.VA, pair.FA, PAIR_OPTIONS, cache=tmp_path)
    assert first.computed.get("preprocess") == 1 and not first.from_cache
    again = symembed.Shape(pair.VA, pair.FA, PAIR_OPTIONS, cache=tmp_path)
    assert not again.computed, again.computed
    assert again.from_cache.get("preprocess") == 1 and again.from_cache.get("embedding") == 1
    np.testing.assert_array_equal(again.embedding, first.embedding)
    # A mesh with one coordinate changed is another key.
    moved = pair.VA.copy()
    moved[0, 0] += 1e-9
    other = symembed.Shape(moved, pair.FA, PAIR_OPTIONS, cache=tmp_path)
    assert other.computed.get("preprocess") == 1
