(function () {
  'use strict';
  var statusEl = document.getElementById('report-status');
  var problems = [];
  var parts = [];
  function fail(message) {
    problems.push(String(message));
    statusEl.textContent = 'error: ' + problems.join(' | ');
    statusEl.setAttribute('data-state', 'error');
  }
  window.addEventListener('error', function (e) { fail((e && e.message) || 'script error'); });
  window.addEventListener('unhandledrejection', function (e) {
    fail('unhandled rejection: ' + (e && e.reason));
  });

  // "#view" (with "&t=1.5": paused at 1.5 s): the 3D view alone, filling the window.
  if (/(?:^|[#&])view(?:&|$)/.test(window.location.hash)) document.body.classList.add('view-only');

  var palette = ['#1b9e77', '#d95f02', '#7570b3', '#e7298a', '#66a61e', '#e6ab02', '#a6761d',
                 '#666666', '#1f78b4', '#b15928', '#6a3d9a', '#b2df8a'];

  function bytesOf(b64) {
    var s = atob(b64), u = new Uint8Array(s.length);
    for (var i = 0; i < s.length; i++) u[i] = s.charCodeAt(i);
    return u;
  }
  // Little-endian uint16, whatever the machine's byte order.
  function uint16Of(b64) {
    var u = bytesOf(b64), out = new Uint16Array(u.length >> 1);
    for (var i = 0; i < out.length; i++) out[i] = u[2 * i] | (u[2 * i + 1] << 8);
    return out;
  }

  // ---- charts ---------------------------------------------------------------------------------
  var chartCount = 0;
  function lineChart(canvas, datasets, xTitle, yTitle, title, xMax) {
    var chart = new Chart(canvas.getContext('2d'), {
      type: 'line',
      data: { datasets: datasets },
      options: {
        animation: false, responsive: true, maintainAspectRatio: false, parsing: false,
        interaction: { mode: 'nearest', intersect: false },
        plugins: {
          title: { display: !!title, text: title || '' },
          legend: { labels: { boxWidth: 12, font: { size: 11 } } }
        },
        scales: {
          x: { type: 'linear', title: { display: true, text: xTitle }, max: xMax },
          y: { type: 'linear', title: { display: true, text: yTitle } }
        },
        elements: { point: { radius: 0 }, line: { borderWidth: 1.5 } }
      }
    });
    chartCount++;
    return chart;
  }
  function dataset(label, points, colour, dashed) {
    return { label: label, data: points, borderColor: colour, backgroundColor: colour,
             borderDash: dashed ? [6, 4] : [], spanGaps: false };
  }

  function setupTrajectories(t) {
    var canvas = document.getElementById('chart-trajectories');
    var select = document.getElementById('trajectory-marker');
    if (!canvas || !select || !t) return;
    function points(values) {
      return t.times.map(function (time, k) {
        var v = values[k];
        return { x: time, y: v === null ? NaN : v };
      });
    }
    function datasetsFor(choice) {
      if (choice === 'all') {
        return t.markers.map(function (m, i) {
          var d = m.x.map(function (x, k) {
            var y = m.y[k], z = m.z[k];
            return x === null || y === null || z === null ? null : Math.sqrt(x * x + y * y + z * z);
          });
          return dataset(m.label, points(d), palette[i % palette.length]);
        });
      }
      var m = t.markers[Number(choice)];
      return ['x', 'y', 'z'].map(function (a, i) {
        return dataset(m.label + ' ' + a, points(m[a]), palette[i]);
      });
    }
    var all = document.createElement('option');
    all.value = 'all';
    all.textContent = 'every marker: distance from its first position';
    select.appendChild(all);
    t.markers.forEach(function (m, i) {
      var o = document.createElement('option');
      o.value = String(i);
      o.textContent = m.label + ': x, y, z';
      select.appendChild(o);
    });
    var chart = lineChart(canvas, datasetsFor('all'), 'time (s)', 'motion (mm)', null);
    select.addEventListener('change', function () {
      chart.data.datasets = datasetsFor(select.value);
      chart.update();
    });
  }

  function setupSpectra(spectra) {
    if (!spectra) return;
    spectra.links.forEach(function (link, i) {
      var canvas = document.getElementById('chart-spectrum-' + i);
      if (!canvas) return;
      var top = 0, sets = [], fMax = 0;
      link.channels.forEach(function (c, k) {
        var pts = c.amplitude.map(function (a, j) {
          if (j > 0 && a > top) top = a;
          fMax = Math.max(fMax, j * link.bin_hz);
          return { x: j * link.bin_hz, y: a };
        });
        sets.push(dataset(c.name || ('channel ' + k), pts, palette[k]));
      });
      var f = link.frequency_hz, title = link.label;
      if (f !== null) {
        sets.push(dataset('identified', [{ x: f, y: 0 }, { x: f, y: 1.05 * top }], '#c00', true));
        title += ': f = ' + f.toFixed(3) + ' Hz';
        if (link.damping_ratio !== null) title += ', \u03b6 = ' + link.damping_ratio.toFixed(4);
      } else {
        title += ' (' + (link.problem || link.status || 'not measured') + ')';
      }
      lineChart(canvas, sets, 'frequency (Hz)', 'amplitude (' + link.unit + ')', title,
                fMax > 0 ? fMax : undefined);
    });
  }

  // ---- 3D view --------------------------------------------------------------------------------
  var SIDES = 8;
  var levelColours = [[0.75, 0.2, 0.15], [0.2, 0.6, 0.2], [0.2, 0.35, 0.8], [0.0, 0.8, 0.5],
                      [0.8, 0.2, 0.8], [1.0, 0.6, 0.1]];
  var sourceColours = { measured: [0.17, 0.63, 0.17], interpolated: [1.0, 0.69, 0.0],
                        'default': [0.55, 0.55, 0.55], '': [0.55, 0.55, 0.55] };
  var bark = [0.55, 0.42, 0.3];

  // The nodes' layout: which sent nodes each node's displacement is interpolated from.
  function nodeLayout(A) {
    var N = A.nodes, stride = A.node_stride;
    var low = new Int32Array(N), high = new Int32Array(N), weight = new Float32Array(N);
    var sent = [], next = new Int32Array(N), prev = new Int32Array(N), branchOf = new Int32Array(N);
    A.branches.forEach(function (b, bi) {
      var first = b[0], count = b[1], idx = [];
      for (var j = 0; j < count; j += stride) idx.push(j);
      if (count > 0 && (count - 1) % stride !== 0) idx.push(count - 1);
      var base = sent.length;
      for (j = 0; j < count; j++) {
        var qa = Math.min(Math.floor(j / stride), idx.length - 1);
        var qb = Math.min(qa + 1, idx.length - 1);
        var ja = idx[qa], jb = idx[qb];
        low[first + j] = base + qa;
        high[first + j] = base + qb;
        weight[first + j] = jb > ja ? (j - ja) / (jb - ja) : 0;
        prev[first + j] = first + Math.max(j - 1, 0);
        next[first + j] = first + Math.min(j + 1, count - 1);
        branchOf[first + j] = bi;
      }
      idx.forEach(function (q) { sent.push(first + q); });
    });
    if (sent.length !== A.sent_nodes) throw new Error('animation: ' + sent.length + ' sent nodes, the data says ' + A.sent_nodes);
    return { low: low, high: high, weight: weight, sent: sent, next: next, prev: prev, branchOf: branchOf };
  }

  function tangentAt(p, L, i, out) {
    var a = L.prev[i], b = L.next[i];
    var x = p[3 * b] - p[3 * a], y = p[3 * b + 1] - p[3 * a + 1], z = p[3 * b + 2] - p[3 * a + 2];
    var n = Math.sqrt(x * x + y * y + z * z) || 1;
    out[0] = x / n; out[1] = y / n; out[2] = z / n;
  }

  // Ring offsets at rest, parallel-transported along each branch so the tubes do not twist.
  function restRings(rest, radius, L, A) {
    var N = A.nodes, offsets = new Float32Array(N * SIDES * 3), normals = new Float32Array(N * SIDES * 3);
    var tangents = new Float32Array(N * 3), t = [0, 0, 0], n = [0, 0, 0];
    A.branches.forEach(function (b) {
      var first = b[0], count = b[1];
      for (var j = 0; j < count; j++) {
        var i = first + j;
        tangentAt(rest, L, i, t);
        tangents.set(t, 3 * i);
        if (j === 0) { n = Math.abs(t[2]) < 0.9 ? [0, 0, 1] : [1, 0, 0]; }
        var d = n[0] * t[0] + n[1] * t[1] + n[2] * t[2];
        n = [n[0] - d * t[0], n[1] - d * t[1], n[2] - d * t[2]];
        var nl = Math.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) || 1;
        n = [n[0] / nl, n[1] / nl, n[2] / nl];
        var bn = [t[1] * n[2] - t[2] * n[1], t[2] * n[0] - t[0] * n[2], t[0] * n[1] - t[1] * n[0]];
        for (var k = 0; k < SIDES; k++) {
          var th = 2 * Math.PI * k / SIDES, c = Math.cos(th), s = Math.sin(th);
          for (var a = 0; a < 3; a++) {
            var u = c * n[a] + s * bn[a];
            normals[(i * SIDES + k) * 3 + a] = u;
            offsets[(i * SIDES + k) * 3 + a] = u * radius[i];
          }
        }
      }
    });
    return { offsets: offsets, normals: normals, tangents: tangents };
  }

  function tubeIndices(A) {
    var quads = 0;
    A.branches.forEach(function (b) { quads += Math.max(b[1] - 1, 0) * SIDES; });
    var index = new Uint32Array(quads * 6), w = 0;
    A.branches.forEach(function (b) {
      for (var j = 0; j + 1 < b[1]; j++) {
        var r0 = (b[0] + j) * SIDES, r1 = r0 + SIDES;
        for (var k = 0; k < SIDES; k++) {
          var k1 = (k + 1) % SIDES;
          index[w++] = r0 + k; index[w++] = r1 + k; index[w++] = r1 + k1;
          index[w++] = r0 + k; index[w++] = r1 + k1; index[w++] = r0 + k1;
        }
      }
    });
    return index;
  }

  // The motion as sent: rest pose, radii, the sent nodes' positions per frame (16-bit in the box).
  function decodeMotion(A) {
    var N = A.nodes, F = A.frames, bmin = A.box.min, bstep = A.box.step;
    var m = { A: A, N: N, F: F, bmin: bmin, bstep: bstep, rest16: uint16Of(A.rest),
              pos16: uint16Of(A.positions), L: nodeLayout(A) };
    var rad16 = uint16Of(A.radii);
    m.M = m.L.sent.length;
    if (m.pos16.length !== F * m.M * 3) {
      throw new Error('animation: ' + m.pos16.length + ' values, expected ' + F * m.M * 3);
    }
    m.rest = new Float32Array(3 * N);
    m.lo = [1e30, 1e30, 1e30];
    m.hi = [-1e30, -1e30, -1e30];
    for (var i = 0; i < 3 * N; i++) {
      var v = bmin[i % 3] + bstep[i % 3] * m.rest16[i];
      m.rest[i] = v;
      m.lo[i % 3] = Math.min(m.lo[i % 3], v);
      m.hi[i % 3] = Math.max(m.hi[i % 3], v);
    }
    m.size = Math.max(m.hi[0] - m.lo[0], m.hi[1] - m.lo[1], m.hi[2] - m.lo[2], 1e-3);
    m.radius = new Float32Array(N);
    for (i = 0; i < N; i++) {
      var r = A.radius_step > 0 ? rad16[i] * A.radius_step : 0.004 * m.size;
      m.radius[i] = Math.max(r, 0.0012 * m.size);  // twigs stay visible
    }
    m.cur = new Float32Array(3 * N);
    m.disp = new Float32Array(3 * m.M);
    return m;
  }

  // Every node's position at time t into m.cur: the sent nodes interpolated between frames, the
  // others moved by their two sent neighbours' displacements. Returns the frame index.
  function computeNodes(m, t) {
    var fpos = Math.min(Math.max(t / m.A.frame_dt, 0), m.F - 1);
    var f0 = Math.floor(fpos), f1 = Math.min(f0 + 1, m.F - 1), a = fpos - f0;
    var o0 = f0 * m.M * 3, o1 = f1 * m.M * 3, L = m.L;
    for (var q = 0; q < m.M; q++) {
      var s = L.sent[q];
      for (var c = 0; c < 3; c++) {
        var v = m.bmin[c] + m.bstep[c] * ((1 - a) * m.pos16[o0 + 3 * q + c] + a * m.pos16[o1 + 3 * q + c]);
        m.disp[3 * q + c] = v - m.rest[3 * s + c];
      }
    }
    for (var i = 0; i < m.N; i++) {
      var l = L.low[i], h = L.high[i], w = L.weight[i];
      for (c = 0; c < 3; c++) {
        m.cur[3 * i + c] = m.rest[3 * i + c] + (1 - w) * m.disp[3 * l + c] + w * m.disp[3 * h + c];
      }
    }
    return f0;
  }

  // The sent node that moves most: the probe the end-to-end test reads.
  function probeNodeOf(m) {
    var best = 0, most = -1, every = Math.max(1, Math.floor(m.F / 50));
    for (var q = 0; q < m.M; q++) {
      for (var f = 0; f < m.F; f += every) {
        var d2 = 0;
        for (var c = 0; c < 3; c++) {
          var d = m.bstep[c] * (m.pos16[(f * m.M + q) * 3 + c] - m.rest16[3 * m.L.sent[q] + c]);
          d2 += d * d;
        }
        if (d2 > most) { most = d2; best = m.L.sent[q]; }
      }
    }
    return best;
  }

  // Renderer, lights, the Z-up world group, ground grid, camera and orbit controls; null when the
  // browser gives no WebGL.
  function createScene(host, m) {
    var renderer;
    try {
      renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    } catch (e) {
      host.innerHTML = '<div class="fallback">This browser gives the page no WebGL: the 3D view ' +
                       'is off (' + e.message + ').</div>';
      return null;
    }
    var width = host.clientWidth || 800, height = host.clientHeight || 500;
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setSize(width, height);
    renderer.setClearColor(0xe9eef2);
    host.appendChild(renderer.domElement);
    var scene = new THREE.Scene();
    scene.add(new THREE.HemisphereLight(0xffffff, 0x8a9a80, 0.9));
    var sun = new THREE.DirectionalLight(0xffffff, 0.7);
    sun.position.set(1, 2, 1.5);
    scene.add(sun);
    var world = new THREE.Group();
    world.rotation.x = -Math.PI / 2;  // simtree is Z-up, three.js Y-up: (x, y, z) -> (x, z, -y)
    scene.add(world);
    var cx = (m.lo[0] + m.hi[0]) / 2, cy = (m.lo[1] + m.hi[1]) / 2, cz = (m.lo[2] + m.hi[2]) / 2;
    var grid = new THREE.GridHelper(2 * m.size, 20, 0x889988, 0xbbccbb);
    grid.position.set(cx, m.lo[2], -cy);
    scene.add(grid);
    var camera = new THREE.PerspectiveCamera(35, width / height, m.size / 500, m.size * 100);
    camera.position.set(cx, cz + 0.12 * m.size, -cy + 1.9 * m.size);  // in front: looking along +Y
    var controls = new THREE.OrbitControls(camera, renderer.domElement);
    controls.target.set(cx, cz, -cy);
    controls.update();
    return { host: host, renderer: renderer, scene: scene, world: world, camera: camera,
             controls: controls, render: function () { renderer.render(scene, camera); } };
  }

  function setAttribute(geometry, name, attribute) {
    if (geometry.setAttribute) geometry.setAttribute(name, attribute);
    else geometry.addAttribute(name, attribute);  // three.js before r110
  }

  // The branches as tubes rebuilt from m.cur: each ring turned by the rotation taking its rest
  // tangent to the current one (Rodrigues), so the tubes bend with the nodes.
  function createTubes(m, world) {
    var N = m.N, rings = restRings(m.rest, m.radius, m.L, m.A);
    var positions = new Float32Array(N * SIDES * 3), normals = new Float32Array(N * SIDES * 3);
    var colours = new Float32Array(N * SIDES * 3);
    var geometry = new THREE.BufferGeometry();
    var posAttr = new THREE.BufferAttribute(positions, 3), nrmAttr = new THREE.BufferAttribute(normals, 3);
    var colAttr = new THREE.BufferAttribute(colours, 3);
    setAttribute(geometry, 'position', posAttr);
    setAttribute(geometry, 'normal', nrmAttr);
    setAttribute(geometry, 'color', colAttr);
    geometry.setIndex(new THREE.BufferAttribute(tubeIndices(m.A), 1));
    var material = new THREE.MeshLambertMaterial({
      vertexColors: THREE.VertexColors !== undefined ? THREE.VertexColors : true,
      side: THREE.DoubleSide });
    var mesh = new THREE.Mesh(geometry, material);
    mesh.frustumCulled = false;
    world.add(mesh);
    var t1 = [0, 0, 0];
    function turn(src, o, c, ux, uy, uz, k1, out) {
      var vx = src[o], vy = src[o + 1], vz = src[o + 2], d = ux * vx + uy * vy + uz * vz;
      out[0] = c * vx + (uy * vz - uz * vy) + d * ux * k1;
      out[1] = c * vy + (uz * vx - ux * vz) + d * uy * k1;
      out[2] = c * vz + (ux * vy - uy * vx) + d * uz * k1;
    }
    var r = [0, 0, 0];
    return {
      update: function () {
        var cur = m.cur, t0 = rings.tangents;
        for (var i = 0; i < N; i++) {
          tangentAt(cur, m.L, i, t1);
          var ax = t0[3 * i], ay = t0[3 * i + 1], az = t0[3 * i + 2];
          var c = ax * t1[0] + ay * t1[1] + az * t1[2];
          var ux = ay * t1[2] - az * t1[1], uy = az * t1[0] - ax * t1[2], uz = ax * t1[1] - ay * t1[0];
          var k1 = c > -0.999 ? 1 / (1 + c) : 0;
          for (var k = 0; k < SIDES; k++) {
            var o = (i * SIDES + k) * 3;
            turn(rings.offsets, o, c, ux, uy, uz, k1, r);
            positions[o] = cur[3 * i] + r[0];
            positions[o + 1] = cur[3 * i + 1] + r[1];
            positions[o + 2] = cur[3 * i + 2] + r[2];
            turn(rings.normals, o, c, ux, uy, uz, k1, r);
            normals[o] = r[0]; normals[o + 1] = r[1]; normals[o + 2] = r[2];
          }
        }
        posAttr.needsUpdate = true;
        nrmAttr.needsUpdate = true;
      },
      colourBy: function (mode) {
        for (var i = 0; i < N; i++) {
          var b = m.A.branches[m.L.branchOf[i]], c = bark;
          if (mode === 'level') c = levelColours[b[2] % levelColours.length];
          if (mode === 'source') c = sourceColours[b[3]] || sourceColours[''];
          for (var k = 0; k < SIDES; k++) colours.set(c, (i * SIDES + k) * 3);
        }
        colAttr.needsUpdate = true;
      }
    };
  }

  // The rope of the pull, from its node to its anchor until the release.
  function createRope(m, world) {
    var rope = m.A.rope, geometry = new THREE.BufferGeometry(), ends = new Float32Array(6);
    var attribute = new THREE.BufferAttribute(ends, 3);
    setAttribute(geometry, 'position', attribute);
    var line = new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0xcc0000 }));
    line.frustumCulled = false;
    line.visible = false;
    world.add(line);
    return function (t) {
      if (!rope) return;
      var n = rope.node;
      line.visible = t < rope.release_s;
      ends.set([m.cur[3 * n], m.cur[3 * n + 1], m.cur[3 * n + 2],
                rope.anchor[0], rope.anchor[1], rope.anchor[2]]);
      attribute.needsUpdate = true;
    };
  }

  // Play/pause, the time slider, speed and colour; the clock runs on animation frames and, where
  // those do not come (a hidden tab, a headless browser's virtual time), on a timer.
  function setupPlayback(m, view, tubes, rope) {
    var A = m.A, probeNode = probeNodeOf(m);
    var slider = document.getElementById('viewer-time'), clock = document.getElementById('viewer-clock');
    var button = document.getElementById('viewer-play'), probe = document.getElementById('viewer-probe');
    var duration = Math.max(A.duration_s, A.frame_dt * (m.F - 1), 1e-3);
    slider.max = String(duration);
    slider.step = String(A.frame_dt / 4);
    var t = 0, playing = true, speed = 1, last = performance.now();
    var hash = /(?:^|[#&])t=([0-9.]+)/.exec(window.location.hash);
    if (hash) { t = Math.min(parseFloat(hash[1]), duration); playing = false; }
    function show(time) {
      t = time;
      var frame = computeNodes(m, t);
      tubes.update();
      rope(t);
      slider.value = String(t);
      clock.textContent = t.toFixed(2) + ' s';
      button.textContent = playing ? 'Pause' : 'Play';
      probe.textContent = JSON.stringify({ t: Number(t.toFixed(4)), frame: frame, node: probeNode,
        position: [m.cur[3 * probeNode], m.cur[3 * probeNode + 1], m.cur[3 * probeNode + 2]] });
      view.render();
    }
    function advance() {
      var now = performance.now();
      if (playing) {
        t += (now - last) / 1000 * speed;
        if (t > duration) t = t % duration;
      }
      last = now;
      show(t);
    }
    button.addEventListener('click', function () { playing = !playing; last = performance.now(); show(t); });
    slider.addEventListener('input', function () { playing = false; show(parseFloat(slider.value)); });
    document.getElementById('viewer-speed').addEventListener('change', function (e) {
      speed = parseFloat(e.target.value);
    });
    document.getElementById('viewer-colour').addEventListener('change', function (e) {
      tubes.colourBy(e.target.value);
      show(t);
    });
    view.controls.addEventListener('change', view.render);
    window.addEventListener('resize', function () {
      var w = view.host.clientWidth || 800, h = view.host.clientHeight || 500;
      view.renderer.setSize(w, h);
      view.camera.aspect = w / h;
      view.camera.updateProjectionMatrix();
      show(t);
    });
    show(t);
    function loop() { advance(); window.requestAnimationFrame(loop); }
    window.requestAnimationFrame(loop);
    window.setInterval(advance, 200);
    window.simtreeViewer = {
      show: show, duration: duration,
      play: function () { playing = true; last = performance.now(); },
      pause: function () { playing = false; }
    };
  }

  function setupViewer(A) {
    var host = document.getElementById('viewer-canvas');
    if (!host || !A) return null;
    var m = decodeMotion(A);
    var view = createScene(host, m);
    if (!view) return 'no WebGL';
    var tubes = createTubes(m, view.world);
    tubes.colourBy('bark');
    setupPlayback(m, view, tubes, createRope(m, view.world));
    return 'WebGL';
  }

  function run(name, f) {
    try { return f(); } catch (e) { fail(name + ': ' + (e && e.message ? e.message : e)); return null; }
  }
  var data = run('data', function () {
    var el = document.getElementById('simtree-data');
    return el ? JSON.parse(el.textContent) : {};
  }) || {};
  var libraries = typeof THREE !== 'undefined' && typeof Chart !== 'undefined';
  if (libraries) {
    run('trajectories', function () { setupTrajectories(data.trajectories); });
    run('spectra', function () { setupSpectra(data.spectra); });
    var viewer = run('3D view', function () { return setupViewer(data.animation); });
    if (viewer) parts.push('3D view (' + viewer + ')');
    statusEl.setAttribute('data-viewer', viewer || 'none');
  } else {
    parts.push('no JavaScript libraries in this page');
  }
  statusEl.setAttribute('data-charts', String(chartCount));
  parts.push(chartCount + ' charts');
  if (problems.length === 0) {
    statusEl.textContent = 'ok: ' + parts.join(', ');
    statusEl.setAttribute('data-state', 'ok');
  }
})();
