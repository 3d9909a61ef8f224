// The report's side files (eval/html/side_files.h): scripts under shapes/ and pairs/ that call
// symembedData(kind, key, payload), added to the page on demand because a page opened from
// file:// may not fetch() local files; their arrays are inflated with the browser's
// DecompressionStream. Exposed as window.SymembedSideFiles: shapeData(name), pairData(key, S, T).
'use strict';

window.SymembedSideFiles = (function () {
  const R = window.SYMEMBED_REPORT;

  const sideData = new Map();
  const loading = new Map();
  window.symembedData = function (kind, key, payload) {
    sideData.set(kind + ':' + key, payload);
  };

  function loadSide(kind, key, file) {
    const id = kind + ':' + key;
    if (sideData.has(id)) return Promise.resolve(sideData.get(id));
    if (loading.has(id)) return loading.get(id);
    const promise = new Promise((resolve, reject) => {
      const script = document.createElement('script');
      script.src = file.split('/').map(encodeURIComponent).join('/');
      script.onload = () => (sideData.has(id) ? resolve(sideData.get(id))
        : reject(new Error(file + ' did not register ' + id)));
      script.onerror = () => reject(new Error('cannot load ' + file + ' (was the report folder moved or cut short?)'));
      document.head.appendChild(script);
    }).finally(() => loading.delete(id));
    loading.set(id, promise);
    return promise;
  }

  async function inflate(bytes) {
    if (typeof DecompressionStream === 'undefined') {
      throw new Error('this browser has no DecompressionStream, which reading the side files needs; use a current Chrome, Firefox or Safari');
    }
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
    return new Uint8Array(await new Response(stream).arrayBuffer());
  }

  const ARRAY_TYPES = { u8: Uint8Array, u16: Uint16Array, u32: Uint32Array };

  // An encoded array of eval/html/side_files.h as its raw typed array (shift not applied).
  async function decodeRaw(encoded, what) {
    const Type = ARRAY_TYPES[encoded.type];
    if (!Type) throw new Error(what + ': unknown array type ' + encoded.type);
    const text = atob(encoded.zlib);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    const raw = await inflate(bytes);
    if (raw.byteLength !== encoded.count * Type.BYTES_PER_ELEMENT) {
      throw new Error(what + ': ' + raw.byteLength + ' bytes, expected ' + encoded.count * Type.BYTES_PER_ELEMENT);
    }
    return new Type(raw.buffer, raw.byteOffset, encoded.count);
  }

  async function decodeIds(encoded, what) {
    const raw = await decodeRaw(encoded, what);
    const ids = new Int32Array(raw.length);
    const shift = encoded.shift || 0;
    for (let i = 0; i < raw.length; ++i) ids[i] = raw[i] - shift;
    return ids;
  }

  async function decodePositions(encoded, what) {
    const q = await decodeRaw(encoded, what);
    const positions = new Float32Array(q.length);
    for (let i = 0; i < q.length; ++i) {
      const k = i % 3;
      positions[i] = encoded.lo[k] + (q[i] / 65535) * (encoded.hi[k] - encoded.lo[k]);
    }
    return positions;
  }

  // Unit values: [0, 1] fractions of "max", -1 for unknown.
  async function decodeUnit(encoded, what) {
    const q = await decodeRaw(encoded, what);
    const values = new Float32Array(q.length);
    for (let i = 0; i < q.length; ++i) values[i] = q[i] === 255 ? -1 : q[i] / 254;
    return values;
  }

  const shapes = new Map();  // id -> Promise of the decoded shape

  // name: the shape's id in R.shapes (its name, or for another mesh under the name the id the
  // pair row gives as source_shape / target_shape).
  function shapeData(name) {
    if (shapes.has(name)) return shapes.get(name);
    const promise = (async () => {
      const info = R.shapes[name];
      if (!info) throw new Error('shape ' + name + ' is not in this report');
      if (info.unavailable) throw new Error('shape ' + name + ': ' + info.unavailable);
      const p = await loadSide('shape', name, info.file);
      const what = info.file;
      const shape = {
        name,
        vertices: p.vertices,
        positions: await decodePositions(p.positions, what + ' positions'),
        faces: await decodeIds(p.faces, what + ' faces'),
        gt: p.gt ? await decodeIds(p.gt, what + ' gt') : null,
        gtSym: p.gt_sym ? await decodeIds(p.gt_sym, what + ' gt_sym') : null,
        gtNote: p.gt_note || null,
      };
      shape.graph = SymembedTransfer.adjacency(shape.vertices, shape.faces);
      sideData.delete('shape:' + name);  // the decoded arrays replace the text
      return shape;
    })();
    promise.catch(() => shapes.delete(name));
    shapes.set(name, promise);
    return promise;
  }

  // The pair's map and errors; the map's coding needs both meshes (S, T from shapeData).
  async function pairData(key, S, T) {
    const view = { key, file: 'pairs/' + key + '.js' };
    const p = await loadSide('pair', view.key, view.file);
    if (p.map.coding !== 'ranks') throw new Error(view.file + ': unknown map coding ' + p.map.coding);
    const ranks = await decodeRaw(p.map.ranks, view.file + ' map ranks');
    const ids = await decodeIds(p.map.ids, view.file + ' map ids');
    sideData.delete('pair:' + view.key);
    return {
      map: SymembedTransfer.decodeVertexMap(ranks, ids, S, T),
      errors: p.errors ? await decodeUnit(p.errors, view.file + ' errors') : null,
      errorMax: p.errors ? p.errors.max : null,
      errorsNote: p.errors_note || null,
    };
  }

  return { shapeData, pairData };
})();
