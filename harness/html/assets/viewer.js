// A small WebGL viewer: one canvas split into panels, each showing one triangle mesh with
// per-vertex colours under a head light. All panels share one camera rotation and zoom (drag
// to orbit, wheel to zoom, double-click to reset), each centred on its own mesh, so a source
// and its targets turn together.
'use strict';

window.SymembedViewer = (function () {
  const VERTEX_SHADER = `
attribute vec3 position;
attribute vec3 normal;
attribute vec3 colour;
uniform mat4 modelView;
uniform mat4 projection;
varying vec3 vNormal;
varying vec3 vColour;
void main() {
  vNormal = (modelView * vec4(normal, 0.0)).xyz;
  vColour = colour;
  gl_Position = projection * modelView * vec4(position, 1.0);
}`;
  // Two-sided head light: meshes from datasets are not always consistently oriented.
  const FRAGMENT_SHADER = `
precision mediump float;
varying vec3 vNormal;
varying vec3 vColour;
void main() {
  vec3 n = normalize(vNormal);
  float light = 0.35 + 0.65 * abs(n.z);
  gl_FragColor = vec4(vColour * light, 1.0);
}`;
  const BACKGROUND = [0.97, 0.97, 0.97];

  // 3 x 3 rotations as row-major arrays of 9.
  function multiply3(a, b) {
    const c = new Array(9).fill(0);
    for (let i = 0; i < 3; ++i) {
      for (let j = 0; j < 3; ++j) {
        for (let k = 0; k < 3; ++k) c[3 * i + j] += a[3 * i + k] * b[3 * k + j];
      }
    }
    return c;
  }

  function axisRotation(axis, angle) {
    const c = Math.cos(angle), s = Math.sin(angle);
    if (axis === 0) return [1, 0, 0, 0, c, -s, 0, s, c];
    if (axis === 1) return [c, 0, s, 0, 1, 0, -s, 0, c];
    return [c, -s, 0, s, c, 0, 0, 0, 1];
  }

  // Named starting views: which model axis points up on the screen.
  const PRESETS = {
    'y up': [1, 0, 0, 0, 1, 0, 0, 0, 1],
    'z up': axisRotation(0, -Math.PI / 2),
    'x up': axisRotation(2, Math.PI / 2),
  };

  // Column-major 4 x 4 for WebGL: modelView = translate(0, 0, -distance) * R * scale * translate(-centre).
  function modelViewMatrix(rotation, centre, scale, distance) {
    const m = new Float32Array(16);
    for (let i = 0; i < 3; ++i) {
      for (let j = 0; j < 3; ++j) m[4 * j + i] = rotation[3 * i + j] * scale;
      let t = 0;
      for (let j = 0; j < 3; ++j) t -= rotation[3 * i + j] * scale * centre[j];
      m[12 + i] = t;
    }
    m[14] -= distance;
    m[15] = 1;
    return m;
  }

  function perspective(fovY, aspect, near, far) {
    const f = 1 / Math.tan(fovY / 2);
    const m = new Float32Array(16);
    m[0] = f / aspect;
    m[5] = f;
    m[10] = (far + near) / (near - far);
    m[11] = -1;
    m[14] = (2 * far * near) / (near - far);
    return m;
  }

  // Area-weighted vertex normals.
  function vertexNormals(positions, faces) {
    const normals = new Float32Array(positions.length);
    for (let f = 0; f < faces.length; f += 3) {
      const a = 3 * faces[f], b = 3 * faces[f + 1], c = 3 * faces[f + 2];
      const ux = positions[b] - positions[a], uy = positions[b + 1] - positions[a + 1];
      const uz = positions[b + 2] - positions[a + 2];
      const vx = positions[c] - positions[a], vy = positions[c + 1] - positions[a + 1];
      const vz = positions[c + 2] - positions[a + 2];
      const nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      for (const v of [a, b, c]) {
        normals[v] += nx;
        normals[v + 1] += ny;
        normals[v + 2] += nz;
      }
    }
    for (let v = 0; v < normals.length; v += 3) {
      const length = Math.hypot(normals[v], normals[v + 1], normals[v + 2]) || 1;
      normals[v] /= length;
      normals[v + 1] /= length;
      normals[v + 2] /= length;
    }
    return normals;
  }

  function compile(gl, type, source) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
      throw new Error('WebGL shader: ' + gl.getShaderInfoLog(shader));
    }
    return shader;
  }

  class Viewer {
    // canvas: the element; panels: how many; columns: panels per row.
    constructor(canvas, panels, columns) {
      const attributes = { antialias: true, preserveDrawingBuffer: true };
      const gl = canvas.getContext('webgl2', attributes) || canvas.getContext('webgl', attributes);
      if (!gl) throw new Error('WebGL is not available in this browser, so the 3D view cannot be drawn');
      this.gl = gl;
      this.canvas = canvas;
      this.columns = columns;
      this.rows = Math.ceil(panels / columns);
      this.meshes = new Array(panels).fill(null);
      this.wideIndices = typeof WebGL2RenderingContext !== 'undefined' &&
        gl instanceof WebGL2RenderingContext || !!gl.getExtension('OES_element_index_uint');
      const program = gl.createProgram();
      gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, VERTEX_SHADER));
      gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, FRAGMENT_SHADER));
      gl.linkProgram(program);
      if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
        throw new Error('WebGL program: ' + gl.getProgramInfoLog(program));
      }
      this.program = program;
      this.location = {
        position: gl.getAttribLocation(program, 'position'),
        normal: gl.getAttribLocation(program, 'normal'),
        colour: gl.getAttribLocation(program, 'colour'),
        modelView: gl.getUniformLocation(program, 'modelView'),
        projection: gl.getUniformLocation(program, 'projection'),
      };
      this.preset = 'y up';
      this.resetView();
      this.pending = false;
      this.trianglesDrawn = 0;
      this.listen();
    }

    resetView(preset) {
      if (preset) this.preset = preset;
      this.rotation = PRESETS[this.preset].slice();
      this.zoom = 1;
      this.render();
    }

    // positions: Float32Array 3n; faces: Uint32Array 3m; colours: Float32Array 3n in [0, 1].
    setMesh(panel, positions, faces, colours) {
      const gl = this.gl;
      const n = positions.length / 3;
      if (n > 65535 && !this.wideIndices) {
        throw new Error('this browser\'s WebGL cannot index ' + n + ' vertices');
      }
      const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
      for (let i = 0; i < positions.length; i += 3) {
        for (let k = 0; k < 3; ++k) {
          lo[k] = Math.min(lo[k], positions[i + k]);
          hi[k] = Math.max(hi[k], positions[i + k]);
        }
      }
      const centre = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
      const radius = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2 || 1;
      const buffer = (target, data) => {
        const b = gl.createBuffer();
        gl.bindBuffer(target, b);
        gl.bufferData(target, data, gl.STATIC_DRAW);
        return b;
      };
      const indices = n > 65535 ? new Uint32Array(faces) : new Uint16Array(faces);
      this.meshes[panel] = {
        position: buffer(gl.ARRAY_BUFFER, positions),
        normal: buffer(gl.ARRAY_BUFFER, vertexNormals(positions, faces)),
        colour: buffer(gl.ARRAY_BUFFER, colours),
        index: buffer(gl.ELEMENT_ARRAY_BUFFER, indices),
        indexType: n > 65535 ? gl.UNSIGNED_INT : gl.UNSIGNED_SHORT,
        count: indices.length,
        centre,
        scale: 1 / radius,
      };
      this.render();
    }

    setColours(panel, colours) {
      const mesh = this.meshes[panel];
      if (!mesh) return;
      this.gl.bindBuffer(this.gl.ARRAY_BUFFER, mesh.colour);
      this.gl.bufferData(this.gl.ARRAY_BUFFER, colours, this.gl.STATIC_DRAW);
      this.render();
    }

    render() {
      if (this.pending) return;
      this.pending = true;
      requestAnimationFrame(() => {
        this.pending = false;
        this.draw();
      });
    }

    draw() {
      const gl = this.gl;
      const ratio = window.devicePixelRatio || 1;
      const width = Math.max(1, Math.round(this.canvas.clientWidth * ratio));
      const height = Math.max(1, Math.round(this.canvas.clientHeight * ratio));
      if (this.canvas.width !== width || this.canvas.height !== height) {
        this.canvas.width = width;
        this.canvas.height = height;
      }
      gl.disable(gl.SCISSOR_TEST);
      gl.clearColor(BACKGROUND[0], BACKGROUND[1], BACKGROUND[2], 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.enable(gl.DEPTH_TEST);
      gl.enable(gl.SCISSOR_TEST);
      gl.useProgram(this.program);
      const panelWidth = Math.floor(width / this.columns);
      const panelHeight = Math.floor(height / this.rows);
      let triangles = 0;
      this.meshes.forEach((mesh, panel) => {
        if (!mesh) return;
        const column = panel % this.columns;
        const row = Math.floor(panel / this.columns);
        const x = column * panelWidth;
        const y = height - (row + 1) * panelHeight;  // WebGL's origin is the bottom left
        gl.viewport(x, y, panelWidth, panelHeight);
        gl.scissor(x, y, panelWidth, panelHeight);
        const distance = 3.2 / this.zoom;
        gl.uniformMatrix4fv(this.location.modelView, false,
          modelViewMatrix(this.rotation, mesh.centre, mesh.scale, distance));
        gl.uniformMatrix4fv(this.location.projection, false,
          perspective(Math.PI / 5, panelWidth / panelHeight, 0.05, 50));
        for (const name of ['position', 'normal', 'colour']) {
          gl.bindBuffer(gl.ARRAY_BUFFER, mesh[name]);
          gl.enableVertexAttribArray(this.location[name]);
          gl.vertexAttribPointer(this.location[name], 3, gl.FLOAT, false, 0, 0);
        }
        gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, mesh.index);
        gl.drawElements(gl.TRIANGLES, mesh.count, mesh.indexType, 0);
        triangles += mesh.count / 3;
      });
      this.trianglesDrawn = triangles;
      this.canvas.dataset.trianglesDrawn = String(triangles);
    }

    listen() {
      let last = null;
      const canvas = this.canvas;
      canvas.addEventListener('pointerdown', (event) => {
        last = [event.clientX, event.clientY];
        canvas.setPointerCapture(event.pointerId);
      });
      canvas.addEventListener('pointermove', (event) => {
        if (!last) return;
        const dx = event.clientX - last[0], dy = event.clientY - last[1];
        last = [event.clientX, event.clientY];
        // Rotations about the screen's axes, applied after the current one.
        const turn = multiply3(axisRotation(0, dy * 0.01), axisRotation(1, dx * 0.01));
        this.rotation = multiply3(turn, this.rotation);
        this.render();
      });
      const stop = () => { last = null; };
      canvas.addEventListener('pointerup', stop);
      canvas.addEventListener('pointercancel', stop);
      canvas.addEventListener('wheel', (event) => {
        event.preventDefault();
        this.zoom = Math.min(20, Math.max(0.2, this.zoom * Math.exp(-event.deltaY * 0.001)));
        this.render();
      }, { passive: false });
      canvas.addEventListener('dblclick', () => this.resetView());
      if (typeof ResizeObserver !== 'undefined') {
        new ResizeObserver(() => this.render()).observe(canvas);
      }
    }
  }

  return { Viewer, presets: Object.keys(PRESETS) };
})();
