// Colours of the pair view: a smooth colouring of the source, carried to the target through a
// vertex map (or the ground truth's lines), and the per-point error as a heat map. Target
// vertices no map entry reaches (a map need not be onto) take the colour of the nearest
// reached vertex along mesh edges, and are counted.
'use strict';

window.SymembedTransfer = (function () {
  // Vertex adjacency from triangles, as compressed rows: neighbours of v are
  // index[start[v] .. start[v + 1]).
  function adjacency(vertices, faces) {
    const degree = new Uint32Array(vertices + 1);
    for (let f = 0; f < faces.length; f += 3) {
      for (let k = 0; k < 3; ++k) degree[faces[f + k]] += 2;
    }
    const start = new Uint32Array(vertices + 1);
    for (let v = 0; v < vertices; ++v) start[v + 1] = start[v] + degree[v];
    const fill = start.slice(0, vertices);
    const index = new Uint32Array(start[vertices]);
    for (let f = 0; f < faces.length; f += 3) {
      for (let k = 0; k < 3; ++k) {
        const a = faces[f + k], b = faces[f + (k + 1) % 3], c = faces[f + (k + 2) % 3];
        index[fill[a]++] = b;
        index[fill[a]++] = c;
      }
    }
    return { start, index };
  }

  // RGB from the position in the bounding box: smooth, and different on the two sides of
  // every axis, so a map that swaps left and right shows it.
  function smoothColours(positions) {
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < positions.length; i += 3) {
      for (let k = 0; k < 3; ++k) {
        lo[k] = Math.min(lo[k], positions[i + k]);
        hi[k] = Math.max(hi[k], positions[i + k]);
      }
    }
    const colours = new Float32Array(positions.length);
    for (let i = 0; i < positions.length; i += 3) {
      for (let k = 0; k < 3; ++k) {
        const t = hi[k] > lo[k] ? (positions[i + k] - lo[k]) / (hi[k] - lo[k]) : 0.5;
        colours[i + k] = 0.1 + 0.85 * t;
      }
    }
    return colours;
  }

  // Per-vertex values (stride numbers each) from values at some vertices: the mean where
  // several land on one vertex, the nearest reached vertex's (breadth-first along edges)
  // elsewhere. ids[i] is the vertex of value i (values[stride * i ...]); ids < 0 are skipped.
  // Returns {values, reached (vertices given a value directly), filled (vertices filled)}.
  function spread(vertices, graph, ids, values, stride) {
    const sum = new Float64Array(vertices * stride);
    const count = new Uint32Array(vertices);
    for (let i = 0; i < ids.length; ++i) {
      const v = ids[i];
      if (v < 0 || v >= vertices) continue;
      for (let k = 0; k < stride; ++k) sum[stride * v + k] += values[stride * i + k];
      count[v] += 1;
    }
    const out = new Float32Array(vertices * stride);
    const queue = new Uint32Array(vertices);
    const seen = new Uint8Array(vertices);
    let tail = 0;
    for (let v = 0; v < vertices; ++v) {
      if (count[v] === 0) continue;
      for (let k = 0; k < stride; ++k) out[stride * v + k] = sum[stride * v + k] / count[v];
      seen[v] = 1;
      queue[tail++] = v;
    }
    const reached = tail;
    for (let head = 0; head < tail; ++head) {
      const v = queue[head];
      for (let e = graph.start[v]; e < graph.start[v + 1]; ++e) {
        const u = graph.index[e];
        if (seen[u]) continue;
        seen[u] = 1;
        for (let k = 0; k < stride; ++k) out[stride * u + k] = out[stride * v + k];
        queue[tail++] = u;
      }
    }
    return { values: out, reached, filled: tail - reached, unreached: vertices - tail };
  }

  // Target colours through a map: sources[i] -> targets[i] carries the colour of sources[i].
  function carry(sourceColours, sources, targets, targetVertices, targetGraph) {
    const values = new Float32Array(3 * sources.length);
    const ids = new Int32Array(sources.length);
    for (let i = 0; i < sources.length; ++i) {
      const s = sources[i];
      ids[i] = s >= 0 ? targets[i] : -1;
      if (s < 0) continue;
      values[3 * i] = sourceColours[3 * s];
      values[3 * i + 1] = sourceColours[3 * s + 1];
      values[3 * i + 2] = sourceColours[3 * s + 2];
    }
    return spread(targetVertices, targetGraph, ids, values, 3);
  }

  // A perceptual ramp (viridis at five stops) for t in [0, 1]; grey for unknown (t < 0).
  const RAMP = [[0.267, 0.005, 0.329], [0.231, 0.322, 0.545], [0.129, 0.569, 0.549],
    [0.369, 0.788, 0.384], [0.993, 0.906, 0.144]];
  function heat(t) {
    if (!(t >= 0)) return [0.6, 0.6, 0.6];
    const x = Math.min(1, t) * (RAMP.length - 1);
    const i = Math.min(RAMP.length - 2, Math.floor(x));
    const f = x - i;
    return [0, 1, 2].map((k) => RAMP[i][k] * (1 - f) + RAMP[i + 1][k] * f);
  }

  // Heat colours of per-vertex values in [0, 1] (or < 0 for unknown).
  function heatColours(values) {
    const colours = new Float32Array(3 * values.length);
    for (let v = 0; v < values.length; ++v) colours.set(heat(values[v]), 3 * v);
    return colours;
  }

  // The ground-truth lines of a pair, as PairLines in registry/dataset.cpp: line i where the
  // source and target have a vertex (and the target's mirrored vertex, when it has a mirrored
  // ground truth).
  function pairLines(sourceIds, targetIds, targetSymIds) {
    const n = Math.min(sourceIds.length, targetIds.length);
    const useSym = targetSymIds && targetSymIds.length === targetIds.length;
    const sources = [], targets = [];
    for (let i = 0; i < n; ++i) {
      if (sourceIds[i] < 0 || targetIds[i] < 0) continue;
      if (useSym && targetSymIds[i] < 0) continue;
      sources.push(sourceIds[i]);
      targets.push(targetIds[i]);
    }
    return { sources: Int32Array.from(sources), targets: Int32Array.from(targets) };
  }

  // A vertex map coded by ranks (EncodeVertexMap in eval/html/side_files.h): visit the source
  // breadth first (components from their lowest vertex, neighbours in adjacency order); a
  // vertex with a parent takes the vertex of its rank in the breadth-first enumeration of the
  // target from its parent's image, or (rank 255, and the first of each component) the next id.
  function decodeVertexMap(ranks, ids, source, target) {
    const n = source.vertices;
    if (ranks.length !== n) throw new Error(ranks.length + ' ranks for ' + n + ' source vertices');
    const order = new Int32Array(n);
    const parent = new Int32Array(n).fill(-1);
    const seen = new Uint8Array(n);
    let tail = 0;
    for (let s = 0; s < n; ++s) {
      if (seen[s]) continue;
      seen[s] = 1;
      let head = tail;
      order[tail++] = s;
      for (; head < tail; ++head) {
        const v = order[head];
        for (let e = source.graph.start[v]; e < source.graph.start[v + 1]; ++e) {
          const u = source.graph.index[e];
          if (seen[u]) continue;
          seen[u] = 1;
          parent[u] = v;
          order[tail++] = u;
        }
      }
    }
    const stamp = new Uint32Array(target.vertices);
    const list = new Int32Array(256);
    let current = 0;
    function atRank(from, rank) {
      current += 1;
      let length = 0;
      list[length++] = from;
      stamp[from] = current;
      if (rank === 0) return from;
      for (let head = 0; head < length; ++head) {
        const v = list[head];
        for (let e = target.graph.start[v]; e < target.graph.start[v + 1]; ++e) {
          const u = target.graph.index[e];
          if (stamp[u] === current) continue;
          stamp[u] = current;
          list[length++] = u;
          if (length - 1 === rank) return u;
        }
      }
      return -1;
    }
    const map = new Int32Array(n);
    let nextId = 0;
    for (let i = 0; i < n; ++i) {
      const v = order[i];
      let t;
      if (ranks[i] === 255) {
        if (nextId >= ids.length) throw new Error('vertex map: too few ids');
        t = ids[nextId++];
      } else {
        t = parent[v] < 0 ? -1 : atRank(map[parent[v]], ranks[i]);
      }
      if (!(t >= 0 && t < target.vertices)) throw new Error('vertex map: no target vertex for source vertex ' + v);
      map[v] = t;
    }
    return map;
  }

  return { adjacency, smoothColours, spread, carry, heat, heatColours, pairLines, decodeVertexMap };
})();
