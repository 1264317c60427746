// vdcloth report: a run's frames in a 3D viewer (three.js), its stats.csv as plots (Chart.js) and
// its summary.json as tables, beside a compared run. Data comes as scripts (data/runs.js, one
// script a frame under data/runN/) so that the page works from disk with no server.
'use strict';

const vdcloth = (() => {
  const runs = [];
  const frameData = [];          // per run: Map frame -> meshes
  const frameWaiters = new Map(); // "run:frame" -> callbacks waiting for its script

  // --- data: what data/runs.js and the frame scripts call ---------------------------------------

  function addRun(run) {
    runs.push(run);
    frameData.push(new Map());
  }

  function addFrame(runIndex, frame, meshes) {
    frameData[runIndex].set(frame, meshes);
    const key = runIndex + ':' + frame;
    for (const done of frameWaiters.get(key) || []) done.resolve(meshes);
    frameWaiters.delete(key);
  }

  function frameFile(run, frame) {
    return run.frame_dir + '/' + String(frame).padStart(4, '0') + '.js';
  }

  // The meshes of a frame of a run, loading its script the first time.
  function loadFrame(runIndex, frame) {
    const cached = frameData[runIndex].get(frame);
    if (cached) return Promise.resolve(cached);
    return new Promise((resolve, reject) => {
      const key = runIndex + ':' + frame;
      const first = !frameWaiters.has(key);
      if (first) frameWaiters.set(key, []);
      frameWaiters.get(key).push({ resolve, reject });
      if (!first) return;
      const script = document.createElement('script');
      script.src = frameFile(runs[runIndex], frame);
      script.onerror = () => {
        for (const waiter of frameWaiters.get(key) || []) waiter.reject(new Error('cannot load ' + script.src));
        frameWaiters.delete(key);
      };
      document.head.appendChild(script);
    });
  }

  // Little-endian binary arrays written by `vdcloth report`, base64 encoded.
  function decode(text, Type) {
    const bytes = atob(text);
    const buffer = new ArrayBuffer(bytes.length);
    const view = new Uint8Array(buffer);
    for (let i = 0; i < bytes.length; ++i) view[i] = bytes.charCodeAt(i);
    return new Type(buffer);
  }

  // --- colours: as `vdcloth render` draws them ---------------------------------------------------

  const clothPalette = [[0.80, 0.25, 0.22], [0.93, 0.72, 0.20], [0.22, 0.42, 0.78], [0.30, 0.65, 0.38],
                        [0.60, 0.35, 0.70], [0.90, 0.50, 0.25], [0.25, 0.70, 0.75], [0.85, 0.40, 0.60]];
  const bodyColour = [0.78, 0.74, 0.70];
  const background = 0xf2f2f0;

  // Red at 1 (full resolution), green at 0.1, blue at 0.01, on a log scale (render/rasterizer.cpp).
  function viewFactorColour(v) {
    const low = [0.20, 0.32, 0.85], middle = [0.28, 0.72, 0.35], high = [0.88, 0.28, 0.20];
    const t = Number.isFinite(v) && v > 0 ? Math.min(1, Math.max(0, (Math.log10(v) + 2) / 2)) : 0;
    const [a, b, s] = t < 0.5 ? [low, middle, 2 * t] : [middle, high, 2 * t - 1];
    return [0, 1, 2].map((k) => a[k] + (b[k] - a[k]) * s);
  }

  // What set a face's resolution (the PLY's reason): seen, turned away, out of frame, defocused,
  // motion-blurred, hidden; the swatches of report.css.
  const reasonColours = [[0.88, 0.28, 0.20], [0.94, 0.75, 0.20], [0.35, 0.35, 0.78], [0.24, 0.67, 0.67], [0.67, 0.31, 0.75],
    [0.45, 0.45, 0.45]];

  // --- the 3D viewer -----------------------------------------------------------------------------

  class Viewer {
    constructor(runIndex, container, width, height) {
      this.runIndex = runIndex;
      const box = document.createElement('div');
      box.className = 'viewer';
      const caption = document.createElement('div');
      caption.className = 'caption';
      caption.textContent = runLabel(runs[runIndex]);
      this.canvas = document.createElement('canvas');
      this.canvas.width = width;
      this.canvas.height = height;
      box.append(caption, this.canvas);
      container.append(box);
      this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: true, preserveDrawingBuffer: true });
      this.renderer.setClearColor(background);
      this.scene = new THREE.Scene();
      this.scene.add(new THREE.AmbientLight(0xffffff, 0.45));
      this.light = new THREE.DirectionalLight(0xffffff, 0.65);
      this.scene.add(this.light);
      this.group = new THREE.Group();
      this.scene.add(this.group);
      this.shown = null; // {frame, vertices: {mesh: count}}
    }

    // Replaces what is drawn by the meshes of one frame.
    show(frame, meshes, style) {
      for (const child of this.group.children) {
        child.geometry.dispose();
        child.material.dispose();
      }
      this.group.clear ? this.group.clear() : this.group.remove(...this.group.children);
      const topology = runs[this.runIndex].topology || {};
      const vertices = {};
      const reasonCounts = {};  // per cloth mesh with reasons: faces by reason
      let garment = 0;
      for (const mesh of meshes) {
        const positions = decode(mesh.positions, Float32Array);
        const faces = mesh.faces ? decode(mesh.faces, Uint32Array) : decode(topology[mesh.name], Uint32Array);
        vertices[mesh.name] = positions.length / 3;
        const indexed = new THREE.BufferGeometry();
        indexed.setAttribute('position', new THREE.BufferAttribute(positions, 3));
        indexed.setIndex(new THREE.BufferAttribute(faces, 1));
        indexed.computeVertexNormals();
        if (!mesh.cloth) {
          const material = new THREE.MeshLambertMaterial({ color: new THREE.Color(...bodyColour), side: THREE.DoubleSide });
          const body = new THREE.Mesh(indexed, material);
          body.userData.body = true;
          this.group.add(body);
          continue;
        }
        // Cloth: one colour a face (its garment's or its view factor's), normals kept smooth.
        const corners = indexed.toNonIndexed();
        const colours = new Float32Array(faces.length * 3);
        const values = mesh.view ? decode(mesh.view, Float32Array) : null;
        const reasons = mesh.reason ? decode(mesh.reason, Uint8Array) : null;
        if (reasons) reasonCounts[mesh.name] = reasons.reduce((counts, r) => ((counts[r] = (counts[r] || 0) + 1), counts), {});
        const own = clothPalette[garment % clothPalette.length];
        const colourOf = (f) => {
          if (style.colour === 'view') return viewFactorColour(values ? values[f] : 1);
          if (style.colour === 'reason') return reasonColours[reasons ? Math.min(reasons[f], reasonColours.length - 1) : 0];
          return own;
        };
        for (let f = 0; f < faces.length / 3; ++f) {
          const c = colourOf(f);
          for (let k = 0; k < 3; ++k) colours.set(c, (3 * f + k) * 3);
        }
        corners.setAttribute('color', new THREE.BufferAttribute(colours, 3));
        const material = new THREE.MeshLambertMaterial({
          vertexColors: THREE.VertexColors, side: THREE.DoubleSide,
          polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
        });
        this.group.add(new THREE.Mesh(corners, material));
        if (style.wireframe) {
          const wire = new THREE.Mesh(indexed, new THREE.MeshBasicMaterial({ color: 0x000000, wireframe: true, transparent: true, opacity: 0.3 }));
          this.group.add(wire);
        } else {
          indexed.dispose();
        }
        ++garment;
      }
      this.shown = { frame, vertices, reasons: reasonCounts };
    }

    render(camera) {
      this.light.position.copy(camera.position);
      this.renderer.render(this.scene, camera);
    }

    // Pixels of the last drawing that are not the background (bodies left out if asked).
    countPixels(camera, withBodies) {
      for (const child of this.group.children) if (child.userData.body) child.visible = withBodies;
      this.render(camera);
      const gl = this.renderer.getContext();
      const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
      const pixels = new Uint8Array(4 * w * h);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      const bg = [(background >> 16) & 255, (background >> 8) & 255, background & 255];
      let count = 0;
      for (let i = 0; i < pixels.length; i += 4)
        if (Math.abs(pixels[i] - bg[0]) + Math.abs(pixels[i + 1] - bg[1]) + Math.abs(pixels[i + 2] - bg[2]) > 12) ++count;
      for (const child of this.group.children) child.visible = true;
      this.render(camera);
      return count;
    }
  }

  function runLabel(run) {
    const s = run.summary || {};
    return run.label + ' (' + (s.name || 'run') + ', ' + (s.mode || '?') + ' mode)';
  }

  // --- the page's state ----------------------------------------------------------------------------

  const state = {
    frames: [],        // frames every run has meshes for, in order
    index: 0,
    viewers: [],
    shotCamera: null,
    orbitCamera: null,
    controls: [],
    playing: false,
    showing: Promise.resolve(),
    charts: {},
    framed: false,     // the orbit camera placed on the meshes (runs without a camera)
    cameraIndex: 0,    // which of the run's cameras the shot camera is
  };

  function style() {
    return {
      colour: document.getElementById('colour-choice').value,
      wireframe: document.getElementById('wireframe').checked,
    };
  }

  // The run's cameras (camera.json, or each camera_NAME.json of a scene with several).
  function cameraList() {
    for (const run of runs) {
      const list = run.cameras.filter((c) => c.frames && c.frames.length);
      if (list.length) return list;
    }
    return [];
  }

  // The shot camera chosen (the first, or the one `vdcloth report --camera` or the page chose).
  function cameraData() {
    const list = cameraList();
    return list.length ? list[Math.min(state.cameraIndex, list.length - 1)] : null;
  }

  // Sets the shot camera to the chosen camera at `frame` (its lens too).
  function placeShotCamera(frame) {
    const data = cameraData();
    if (!data) return;
    const key = data.frames.find((k) => k.frame === frame) || data.frames[Math.min(frame, data.frames.length - 1)];
    const camera = state.shotCamera;
    camera.fov = data.fov_y_degrees;
    camera.near = data.near;
    camera.far = data.far;
    camera.updateProjectionMatrix();
    camera.position.set(...key.position);
    camera.up.set(...key.up);
    camera.lookAt(new THREE.Vector3(...key.target));
    camera.updateMatrixWorld();
  }

  function activeCamera() {
    return document.getElementById('camera-choice').value === 'orbit' ? state.orbitCamera : state.shotCamera;
  }

  function drawAll() {
    const camera = activeCamera();
    for (const viewer of state.viewers) viewer.render(camera);
  }

  // Shows the frame at `index` of the timeline in every viewer; resolves once drawn.
  function showIndex(index) {
    state.index = index;
    const frame = state.frames[index];
    const label = document.getElementById('frame-label');
    const data = cameraData();
    const key = data ? data.frames.find((k) => k.frame === frame) : null;
    const time = key ? key.time : frame * ((runs[0].summary || {}).frame_time || 0);
    label.textContent = 'frame ' + frame + '  (' + time.toFixed(2) + ' s' + (key ? ', shot ' + key.shot : '') + ')';
    document.getElementById('timeline').value = index;
    state.showing = Promise.all(state.viewers.map((v) => loadFrame(v.runIndex, frame))).then((all) => {
      if (state.index !== index) return;
      all.forEach((meshes, k) => state.viewers[k].show(frame, meshes, style()));
      if (!cameraData() && !state.framed) frameOrbitCamera();
      placeShotCamera(frame);
      drawAll();
    }).catch((e) => {
      // A frame script missing or broken: said on the page, and kept for the page's own check.
      document.getElementById('viewer-note').textContent = 'Frame ' + frame + ' could not be shown: ' + e.message;
      window.vdclothErrors.push(String(e.message));
    });
    return state.showing;
  }

  // Without a shot camera, the orbit camera starts looking at the first frame's meshes whole.
  function frameOrbitCamera() {
    const box = new THREE.Box3().setFromObject(state.viewers[0].group);
    if (box.isEmpty()) return;
    const centre = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3()).length();
    const distance = size / (2 * Math.tan((state.orbitCamera.fov * Math.PI) / 360)) + size / 2;
    state.orbitCamera.position.copy(centre).add(new THREE.Vector3(0, 0.4, 1).normalize().multiplyScalar(distance));
    for (const controls of state.controls) {
      controls.target.copy(centre);
      controls.update();
    }
    state.framed = true;
  }

  function redraw() {
    return showIndex(state.index);
  }

  function setUpViewer() {
    const container = document.getElementById('viewers');
    const note = document.getElementById('viewer-note');
    state.frames = runs[0].frames.filter((f) => runs.every((r) => r.frames.includes(f)));
    if (!state.frames.length) {
      note.textContent = runs.some((r) => r.frames.length)
        ? 'The runs have no frame meshes in common.'
        : 'This run wrote no frame meshes (--mesh-every 0): nothing to show in 3D.';
      document.getElementById('viewer-section').classList.add('empty');
      return;
    }
    state.cameraIndex = runs[0].initial_camera || 0;
    const choice = document.getElementById('camera-choice');
    const list = cameraList();
    // One choice a camera: "shot camera", or each named camera of a run with several.
    list.forEach((c, k) => {
      const option = k === 0 ? choice.querySelector('option[value="shot"]') : document.createElement('option');
      if (k > 0) option.value = 'shot:' + k;
      option.textContent = c.name ? 'camera ' + c.name : 'shot camera';
      if (k > 0) choice.insertBefore(option, choice.querySelector('option[value="orbit"]'));
    });
    choice.value = state.cameraIndex > 0 ? 'shot:' + state.cameraIndex : 'shot';
    const data = cameraData();
    const width = data ? data.width : 1280, height = data ? data.height : 720;
    const scale = Math.min(1, (runs.length > 1 ? 640 : 960) / width);
    const w = Math.round(width * scale), h = Math.round(height * scale);
    for (let r = 0; r < runs.length; ++r) state.viewers.push(new Viewer(r, container, w, h));
    const fov = data ? data.fov_y_degrees : 40;
    state.shotCamera = new THREE.PerspectiveCamera(fov, width / height, data ? data.near : 0.05, data ? data.far : 100);
    state.orbitCamera = new THREE.PerspectiveCamera(fov, width / height, 0.01, 1000);
    if (data) {
      placeShotCamera(state.frames[0]);
      const key = data.frames[0];
      state.orbitCamera.position.set(...key.position);
    } else {
      state.shotCamera.position.set(0, 1.2, 4);
      state.shotCamera.lookAt(0, 1, 0);
      state.orbitCamera.position.set(0, 1.2, 4);
      document.getElementById('camera-choice').value = 'orbit';
      document.getElementById('camera-choice').disabled = true;
    }
    for (const viewer of state.viewers) {
      const controls = new THREE.OrbitControls(state.orbitCamera, viewer.canvas);
      controls.target.set(...(data ? data.frames[0].target : [0, 1, 0]));
      controls.update();
      controls.addEventListener('change', () => {
        if (document.getElementById('camera-choice').value === 'orbit') drawAll();
      });
      state.controls.push(controls);
    }
    const timeline = document.getElementById('timeline');
    timeline.max = state.frames.length - 1;
    timeline.addEventListener('input', () => showIndex(Number(timeline.value)));
    document.getElementById('camera-choice').addEventListener('change', () => {
      const value = document.getElementById('camera-choice').value;
      if (value !== 'orbit') state.cameraIndex = value.startsWith('shot:') ? Number(value.slice(5)) : 0;
      placeShotCamera(state.frames[state.index]);
      drawAll();
    });
    document.getElementById('colour-choice').addEventListener('change', redraw);
    document.getElementById('wireframe').addEventListener('change', redraw);
    document.getElementById('play').addEventListener('click', togglePlay);
    showIndex(0);
  }

  // Plays the frames at the shot's speed (slower when frames take longer to load).
  function togglePlay() {
    const button = document.getElementById('play');
    state.playing = !state.playing;
    button.textContent = state.playing ? 'Pause' : 'Play';
    if (!state.playing) return;
    const frameTime = (runs[0].summary || {}).frame_time || 0.04;
    const step = () => {
      if (!state.playing) return;
      const next = state.index + 1 < state.frames.length ? state.index + 1 : 0;
      const spacing = Math.max(1, state.frames[next] - state.frames[state.index]);
      const started = performance.now();
      showIndex(next).then(() => {
        const wait = Math.max(0, frameTime * spacing * 1000 - (performance.now() - started));
        setTimeout(step, wait);
      });
    };
    step();
  }

  // --- plots -------------------------------------------------------------------------------------

  const runColours = ['rgb(200, 60, 50)', 'rgb(50, 100, 190)'];

  // Dashed vertical lines at the camera's cuts.
  const cutLines = {
    id: 'cuts',
    afterDatasetsDraw(chart, args, options) {
      const frames = options.frames || [];
      const { ctx, chartArea, scales } = chart;
      ctx.save();
      ctx.strokeStyle = 'rgba(0, 0, 0, 0.55)';
      ctx.setLineDash([5, 4]);
      for (const f of frames) {
        const x = scales.x.getPixelForValue(f);
        if (x < chartArea.left || x > chartArea.right) continue;
        ctx.beginPath();
        ctx.moveTo(x, chartArea.top);
        ctx.lineTo(x, chartArea.bottom);
        ctx.stroke();
      }
      ctx.restore();
    },
  };

  function cuts() {
    const data = cameraData();
    return data ? data.frames.filter((k) => k.cut).map((k) => k.frame) : [];
  }

  function column(run, name) {
    return run.stats[name] || run.stats.frame.map(() => 0);
  }

  function linePlot(canvasId, title, yTitle, name) {
    const datasets = runs.map((run, r) => ({
      label: runLabel(run),
      data: run.stats.frame.map((f, i) => ({ x: f, y: column(run, name)[i] })),
      borderColor: runColours[r % runColours.length],
      backgroundColor: runColours[r % runColours.length],
      pointRadius: 0,
      borderWidth: 1.5,
    }));
    return new Chart(document.getElementById(canvasId), {
      type: 'line',
      data: { datasets },
      options: {
        animation: false,
        maintainAspectRatio: false,
        parsing: false,
        scales: { x: { type: 'linear', title: { display: true, text: 'frame' } }, y: { beginAtZero: true, title: { display: true, text: yTitle } } },
        plugins: { title: { display: true, text: title }, cuts: { frames: cuts() } },
      },
      plugins: [cutLines],
    });
  }

  // Where each frame's time went: stats.csv's timed parts and the rest.
  const parts = [
    ['assemble_seconds', 'forces and Jacobians', 'rgb(230, 159, 0)'],
    ['solve_seconds', 'linear solve', 'rgb(86, 180, 233)'],
    ['remesh_seconds', 'remeshing', 'rgb(0, 158, 115)'],
    ['collision_seconds', 'collisions', 'rgb(213, 94, 0)'],
    ['view_seconds', 'view factors', 'rgb(204, 121, 167)'],
  ];

  function breakdownPlot(run, r) {
    const holder = document.createElement('div');
    holder.className = 'plot';
    const canvas = document.createElement('canvas');
    canvas.id = 'breakdown-plot-' + r;
    holder.append(canvas);
    document.getElementById('breakdown-plots').append(holder);
    const frames = run.stats.frame;
    const datasets = parts.map(([name, label, colour]) => ({
      label, backgroundColor: colour, data: frames.map((f, i) => ({ x: f, y: column(run, name)[i] })),
    }));
    const total = column(run, 'seconds');
    datasets.push({
      label: 'the rest (step control, bookkeeping, writing)',
      backgroundColor: 'rgb(160, 160, 160)',
      data: frames.map((f, i) => ({ x: f, y: Math.max(0, total[i] - parts.reduce((s, [name]) => s + column(run, name)[i], 0)) })),
    });
    return new Chart(canvas, {
      type: 'bar',
      data: { datasets },
      options: {
        animation: false,
        maintainAspectRatio: false,
        parsing: false,
        barPercentage: 1,
        categoryPercentage: 1,
        scales: { x: { type: 'linear', stacked: true, title: { display: true, text: 'frame' } },
                  y: { stacked: true, beginAtZero: true, title: { display: true, text: 'seconds' } } },
        plugins: { title: { display: true, text: 'Where the time of a frame went: ' + runLabel(run) }, cuts: { frames: cuts() } },
      },
      plugins: [cutLines],
    });
  }

  function setUpPlots() {
    state.charts.faces = linePlot('faces-plot', 'Faces per frame (all garments)', 'faces', 'faces');
    state.charts.seconds = linePlot('seconds-plot', 'Seconds per frame (wall time)', 'seconds', 'seconds');
    state.charts.breakdown = runs.map(breakdownPlot);
    // The physics level of detail, where a run used it: how many garment groups no camera
    // resolved, each remeshed only every view.far_remesh_every frames.
    if (runs.some((run) => column(run, 'far_groups').some((n) => n > 0))) {
      document.getElementById('far-holder').hidden = false;
      state.charts.far = linePlot('far-plot', 'Garment groups at the far level of detail (remeshed every far_remesh_every frames)', 'groups',
                                  'far_groups');
    }
  }

  // --- tables ------------------------------------------------------------------------------------

  function table(header, rows, numeric) {
    const t = document.createElement('table');
    const head = t.insertRow();
    for (const h of header) {
      const th = document.createElement('th');
      th.textContent = h;
      head.append(th);
    }
    for (const row of rows) {
      const tr = t.insertRow();
      row.forEach((cell, k) => {
        const td = tr.insertCell();
        td.textContent = cell === undefined || cell === null ? '-' : String(cell);
        if (numeric && numeric(k, cell)) td.className = 'number';
      });
    }
    return t;
  }

  function fixed(x, digits) {
    return typeof x === 'number' ? x.toFixed(digits) : x;
  }

  function setUpTables() {
    const summaries = runs.map((r) => r.summary || {});
    const machine = (s) => (s.machine ? [s.machine.host, s.machine.cpu, s.machine.cores + ' cores'].filter(Boolean).join(', ') : null);
    const rows = [
      ['run directory', ...runs.map((r) => r.label)],
      ['scene', ...summaries.map((s) => s.scene)],
      ['mode', ...summaries.map((s) => s.mode)],
      ['status', ...summaries.map((s) => s.status + (s.error ? ': ' + s.error : ''))],
      ['frames', ...summaries.map((s) => s.frames)],
      ['vdcloth version', ...summaries.map((s) => s.version)],
      ['machine', ...summaries.map(machine)],
      ['threads', ...summaries.map((s) => s.threads)],
      ['finished (UTC)', ...summaries.map((s) => s.finished)],
      ['wall time (s)', ...summaries.map((s) => fixed(s.total_seconds, 1))],
      ['CPU time (s)', ...summaries.map((s) => fixed(s.cpu_seconds, 1))],
      ['seconds a frame, mean', ...summaries.map((s) => fixed((s.seconds_per_frame || {}).mean, 3))],
      ['seconds a frame, max', ...summaries.map((s) => fixed((s.seconds_per_frame || {}).max, 3))],
      ['faces, mean', ...summaries.map((s) => fixed((s.faces || {}).mean, 0))],
      ['faces, min / max', ...summaries.map((s) => (s.faces ? s.faces.min + ' / ' + s.faces.max : null))],
      ['peak memory (MiB)', ...summaries.map((s) => fixed(s.peak_memory_kib / 1024, 1))],
      ['CPU stolen by the host', ...summaries.map((s) => (typeof s.steal === 'number' ? (100 * s.steal).toFixed(1) + '%' : null))],
      ['linear solver', ...summaries.map((s) => s.linear_solver)],
      ['substeps a frame', ...summaries.map((s) => s.substeps)],
      ['segments (resumed runs)', ...summaries.map((s) => s.segments)],
    ];
    if (runs.length > 1) {
      const a = summaries[0].seconds_per_frame, b = summaries[1].seconds_per_frame;
      if (a && b && a.mean > 0) rows.push(['speed against the compared run', (b.mean / a.mean).toFixed(2) + 'x', '1x']);
    }
    document.getElementById('summary-table').append(table(['', ...runs.map(runLabel)], rows, (k) => k > 0));

    const garments = [];
    runs.forEach((run) => {
      for (const g of (run.summary || {}).garments || []) garments.push([run.label, g.name, g.material, g.faces, g.vertices]);
    });
    document.getElementById('garment-table').append(table(['run', 'garment', 'material', 'faces', 'vertices'], garments, (k) => k >= 3));

    const checks = runs.map((run) => {
      if (!run.check) return [run.label, 'not checked (vdcloth check ' + run.label + ' checks it)', '', ''];
      const frames = new Set(run.check.rows.map((row) => row.frame));
      const pairs = run.check.rows.reduce((s, row) => s + row.face_pairs, 0);
      return [run.label, run.check.status, frames.size, pairs];
    });
    document.getElementById('check-table').append(table(['run', 'vdcloth check said', 'frames with crossings', 'crossing face pairs'], checks, (k) => k >= 2));

    const logs = document.getElementById('log-table');
    runs.forEach((run) => {
      const p = document.createElement('p');
      if (!run.log) p.textContent = run.label + ': no log.txt (written by runs of vdcloth 0.1.0 and later).';
      else p.textContent = run.label + ': ' + run.log.length + ' message(s)' + (run.log.length ? ':' : '.');
      logs.append(p);
      if (run.log && run.log.length) {
        const shown = run.log.slice(0, 200).map((line) => [line]);
        if (run.log.length > 200) shown.push(['... and ' + (run.log.length - 200) + ' more in log.txt']);
        const t = table(['message'], shown);
        for (const td of t.querySelectorAll('td')) td.className = 'log-line';
        logs.append(t);
      }
    });
  }

  // --- the page's own check (index.html#selftest): what a browser test reads back -----------------

  async function selfTest() {
    const out = { frames: state.frames, shown: [], plots: {}, tables: {} };
    try {
      const viewer = state.viewers[0];
      const camera = state.shotCamera;
      const shownNow = async (index) => {
        await showIndex(index);
        return {
          label: document.getElementById('frame-label').textContent,
          frames: state.viewers.map((v) => v.shown.frame),
          vertices: state.viewers.map((v) => v.shown.vertices),
          pixels: viewer.countPixels(camera, true),
          cloth_pixels: viewer.countPixels(camera, false),
        };
      };
      out.shown.push(await shownNow(0));
      // Through the timeline, as a user drags it.
      const timeline = document.getElementById('timeline');
      timeline.value = state.frames.length - 1;
      timeline.dispatchEvent(new Event('input'));
      await state.showing;
      out.shown.push({
        label: document.getElementById('frame-label').textContent,
        frames: state.viewers.map((v) => v.shown.frame),
        vertices: state.viewers.map((v) => v.shown.vertices),
        pixels: viewer.countPixels(camera, true),
        cloth_pixels: viewer.countPixels(camera, false),
      });
      document.getElementById('colour-choice').value = 'view';
      document.getElementById('wireframe').checked = true;
      await redraw();
      out.shown.push({ style: 'view wireframe', pixels: viewer.countPixels(camera, true), cloth_pixels: viewer.countPixels(camera, false) });
      document.getElementById('colour-choice').value = 'reason';
      await redraw();
      out.shown.push({ style: 'reason wireframe', cloth_pixels: viewer.countPixels(camera, false), reasons: viewer.shown.reasons });
      // A run with several cameras: each chosen as a user would, and what it shows.
      const choice = document.getElementById('camera-choice');
      out.cameras = Array.from(choice.options).map((o) => [o.value, o.textContent]);
      for (const option of Array.from(choice.options)) {
        if (!option.value.startsWith('shot') || cameraList().length < 2) continue;
        choice.value = option.value;
        choice.dispatchEvent(new Event('change'));
        out.shown.push({ style: option.value, cloth_pixels: viewer.countPixels(camera, false), position: camera.position.toArray() });
      }
    } catch (e) {
      window.vdclothErrors.push('self-test: ' + e);
    }
    const values = (chart) => chart.data.datasets.map((d) => d.data.map((p) => p.y));
    out.plots.faces = values(state.charts.faces);
    out.plots.seconds = values(state.charts.seconds);
    out.plots.breakdown = state.charts.breakdown.map(values);
    out.plots.far = state.charts.far ? values(state.charts.far) : null;
    out.plots.cuts = cuts();
    out.tables.summary = document.getElementById('summary-table').innerText;
    out.tables.log = document.getElementById('log-table').innerText;
    out.errors = window.vdclothErrors;
    const pre = document.getElementById('selftest-result');
    pre.textContent = JSON.stringify(out);
    pre.hidden = false;
  }

  function start() {
    if (!runs.length) {
      document.getElementById('subtitle').textContent = 'No run data: data/runs.js is missing or empty.';
      return;
    }
    const s = runs[0].summary || {};
    document.getElementById('title').textContent = 'vdcloth report: ' + (s.name || runs[0].label);
    document.getElementById('subtitle').textContent = runs.map(runLabel).join(' against ');
    document.title = 'vdcloth report: ' + (s.name || runs[0].label);
    setUpTables();
    setUpPlots();
    setUpViewer();
    if (location.hash === '#selftest') selfTest();
  }

  window.addEventListener('DOMContentLoaded', start);
  return { addRun, addFrame };
})();
