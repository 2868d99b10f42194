// swath-fleet's live and replay page: a run's events.jsonl lines (docs/swath-fleet.md) applied one
// by one to the drones, tasks, forecasts and assignment they describe, drawn with Leaflet: on a map
// in lat/lon (Web Mercator) when the world has a geographic origin (run_start's origin, or
// SWATH_DATA.origin for a live run), else in the run's local frame (x east, y north, metres;
// CRS.Simple: [lat, lng] = [y, x]).
// SWATH_DATA.mode "live": the lines come from the server that sent the page (GET /events, server-
// sent events) as the run writes them; "replay": they are SWATH_DATA.events, with a time slider.
'use strict';
(function () {
  // The drone colours of the plan page and of tracks.png.
  const kDroneColours = ['#d92619', '#8c1abf', '#f28c00', '#008c8c', '#8c5919', '#e6339a'];
  const droneColour = (i) => kDroneColours[((i % 6) + 6) % 6];
  const kTaskColours = {created: '#999999', visible: '#1f77b4', dispatched: '#f2b600',
                        done: '#2ca02c', cancelled: '#7f7f7f', failed: '#111111'};
  const text = (s) => String(s).replace(/[&<>"]/g, (c) => ({'&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;'}[c]));
  const replayed = SWATH_DATA.mode === 'live' ? [] :
      SWATH_DATA.events.split('\n').filter((l) => l.trim() !== '').map((l) => JSON.parse(l));
  const origin = SWATH_DATA.origin || (replayed.length && replayed[0].origin) || null;
  // Local metres to [lat, lon] about the origin: the WGS84 ellipsoid's radii of curvature there
  // (meridian M, prime vertical N), within a millimetre of the tangent plane swath-fleet's frame
  // uses over a few hundred metres.
  const kA_m = 6378137, kE2 = 0.00669437999014, kDeg = Math.PI / 180;
  const frame = origin ? (() => {
    const s = Math.sin(origin.lat_deg * kDeg), w = 1 - kE2 * s * s;
    return {north_m: kA_m * (1 - kE2) / Math.pow(w, 1.5) * kDeg,  // per degree of latitude
            east_m: kA_m / Math.sqrt(w) * Math.cos(origin.lat_deg * kDeg) * kDeg};
  })() : null;
  const ll = frame ? (x, y) => [origin.lat_deg + y / frame.north_m, origin.lon_deg + x / frame.east_m]
                   : (x, y) => [y, x];
  const xy = frame ? (p) => [(p.lng - origin.lon_deg) * frame.east_m, (p.lat - origin.lat_deg) * frame.north_m]
                   : (p) => [p.lng, p.lat];

  document.getElementById('title').textContent = SWATH_DATA.title;
  const map = L.map('map', frame ? {zoomSnap: 0, maxZoom: 24, attributionControl: false}
                                 : {crs: L.CRS.Simple, zoomSnap: 0, minZoom: -12, attributionControl: false});
  map.setView(ll(0, 0), frame ? 18 : 0);
  // Drones above the tasks they stand on (one SVG per pane; paths in a pane stack by age).
  map.createPane('drones').style.zIndex = 650;
  const layers = {
    trails: L.layerGroup().addTo(map), assignments: L.layerGroup().addTo(map),
    forecasts: L.layerGroup().addTo(map), tasks: L.layerGroup().addTo(map),
    drones: L.layerGroup().addTo(map)};
  L.control.layers(null, {'Trails': layers.trails, 'Assignments': layers.assignments,
                          'Forecasts': layers.forecasts, 'Tasks': layers.tasks,
                          'Drones': layers.drones}, {collapsed: false}).addTo(map);
  document.getElementById('legend').innerHTML = Object.entries(kTaskColours).map(([k, c]) =>
    `<div><span class="swatch" style="background:${c}"></span>task ${k}</div>`).join('') +
    '<div><span class="swatch" style="background:#fff;border:1px dashed #1f77b4"></span>forecast</div>';

  // ---- the run's state, from its events ------------------------------------------------------
  let run;
  function fresh() {
    for (const g of Object.values(layers)) g.clearLayers();
    run = {t_s: 0, drones: new Map(), tasks: new Map(), forecasts: [], assignment: [], ended: false,
           fence: null, dirty: true};
  }
  function drone(i) {
    if (!run.drones.has(i))
      run.drones.set(i, {index: i, name: 'drone ' + i, x: null, y: null, soc: null, state: '',
                         trail: [], marker: null, line: null});
    return run.drones.get(i);
  }
  function task(id) {
    if (!run.tasks.has(id)) run.tasks.set(id, {id: id, kind: '', state: 'created', x: null, y: null, marker: null});
    return run.tasks.get(id);
  }
  function move(d, e) {
    if (typeof e.x_m !== 'number' || typeof e.y_m !== 'number') return;
    d.x = e.x_m;
    d.y = e.y_m;
    const last = d.trail[d.trail.length - 1];
    const here = ll(e.x_m, e.y_m);
    if (!last || last[0] !== here[0] || last[1] !== here[1]) d.trail.push(here);
  }
  function apply(e) {
    if (typeof e.t_s === 'number') run.t_s = e.t_s;
    run.dirty = true;
    switch (e.ev) {
      case 'run_start':
        for (const d of e.drones || []) Object.assign(drone(d.drone), {name: d.name, soc: d.soc});
        if (e.envelope && Array.isArray(e.envelope.inclusions) && e.envelope.inclusions.length) {
          run.fence = e.envelope.inclusions[0];
          for (const ring of e.envelope.inclusions)
            L.polygon(ring.map((p) => ll(p[0], p[1])), {color: '#555', weight: 1, fill: false}).addTo(layers.trails);
        }
        for (const ring of (e.envelope && e.envelope.exclusions) || [])
          L.polygon(ring.map((p) => ll(p[0], p[1])), {color: '#bf1a0d', weight: 1, fillOpacity: 0.15}).addTo(layers.trails);
        break;
      case 'drone_state': case 'drone_mode': {
        const d = drone(e.drone);
        move(d, e);
        if (typeof e.soc === 'number') d.soc = e.soc;
        if (e.state) d.state = e.state;
        break;
      }
      case 'abort_command': case 'link_lost': case 'link_up':
        move(drone(e.drone), e);
        break;
      case 'task_created': task(e.task).kind = e.kind; break;
      case 'request_visible': Object.assign(task(e.task), {state: 'visible', x: e.x_m, y: e.y_m}); break;
      case 'dispatch': {
        const t = task(e.task);
        t.state = 'dispatched';
        if (t.x === null) { t.x = e.x_m; t.y = e.y_m; }
        break;
      }
      case 'task_done': task(e.task).state = 'done'; break;
      case 'task_cancelled': task(e.task).state = 'cancelled'; break;
      case 'task_failed': task(e.task).state = 'failed'; break;
      case 'forecast': run.forecasts = e.forecasts || []; break;
      case 'schedule': run.assignment = e.assignment || []; break;
      case 'run_end': run.ended = true; break;
      default: break;
    }
  }

  // ---- drawing ------------------------------------------------------------------------------
  function draw() {
    if (!run.dirty) return;
    run.dirty = false;
    for (const d of run.drones.values()) {
      if (d.x === null) continue;
      const colour = droneColour(d.index);
      if (!d.marker) {
        d.line = L.polyline([], {color: colour, weight: 2, opacity: 0.6}).addTo(layers.trails);
        d.marker = L.circleMarker(ll(d.x, d.y), {radius: 7, color: '#000', weight: 1, fillColor: colour,
                                                 fillOpacity: 1, pane: 'drones'}).addTo(layers.drones);
        d.marker.bindTooltip('');
      }
      d.marker.setLatLng(ll(d.x, d.y));
      d.marker.setTooltipContent(`${text(d.name)}: ${text(d.state)}` +
                                 (d.soc === null ? '' : `, ${Math.round(d.soc * 100)} %`));
      d.line.setLatLngs(d.trail);
    }
    for (const t of run.tasks.values()) {
      if (t.x === null || typeof t.x !== 'number') continue;
      if (!t.marker) {
        t.marker = L.circleMarker(ll(t.x, t.y), {radius: 5, weight: 1, color: '#000', fillOpacity: 0.9})
                       .addTo(layers.tasks);
        t.marker.bindTooltip('');
      }
      t.marker.setStyle({fillColor: kTaskColours[t.state]});
      t.marker.setTooltipContent(`task ${t.id} ${text(t.kind)}: ${t.state}`);
    }
    layers.forecasts.clearLayers();
    for (const f of run.forecasts)
      L.circleMarker(ll(f.x_m, f.y_m), {radius: 6, color: '#1f77b4', dashArray: '3 3', fill: false})
          .bindTooltip(`forecast ${text(f.kind)}: p ${f.p}, at ${f.expected_s} s`).addTo(layers.forecasts);
    layers.assignments.clearLayers();
    for (const a of run.assignment) {
      const d = run.drones.get(a.drone);
      const t = a.task === undefined ? null : run.tasks.get(a.task);
      if (!d || d.x === null || !t || t.x === null) continue;
      L.polyline([ll(d.x, d.y), ll(t.x, t.y)], {color: droneColour(d.index), weight: 1, dashArray: '4 4'})
          .addTo(layers.assignments);
    }
    drawPanel();
  }
  function drawPanel() {
    const rows = [...run.drones.values()].map((d) =>
      `<tr><td><span class="swatch" style="background:${droneColour(d.index)}"></span>${text(d.name)}</td>` +
      `<td>${text(d.state)}</td><td>${d.soc === null ? '' : Math.round(d.soc * 100) + ' %'}</td></tr>`);
    document.getElementById('drones').innerHTML = rows.join('');
    const counts = {};
    for (const t of run.tasks.values()) counts[t.state] = (counts[t.state] || 0) + 1;
    document.getElementById('tasks').innerHTML = Object.entries(counts).map(([k, n]) =>
      `<div><span class="swatch" style="background:${kTaskColours[k]}"></span>${n} ${k}</div>`).join('');
    document.getElementById('status').textContent =
        `t = ${run.t_s.toFixed(1)} s` + (run.ended ? ' (run ended)' : '') +
        (SWATH_DATA.mode === 'live' ? ` · ${live.messages} events received` : '');
  }
  // The view: the fence when the run has one, else every place seen so far.
  let fitted = null;
  function fit(points) {
    const b = L.latLngBounds(run.fence ? run.fence.map((p) => ll(p[0], p[1])) : points);
    if (!b.isValid()) return;
    if (fitted && fitted.contains(b)) return;
    fitted = b.pad(0.1);
    map.fitBounds(fitted, {padding: [20, 20]});
  }
  function places() {
    const p = [];
    for (const d of run.drones.values()) p.push(...d.trail);
    for (const t of run.tasks.values()) if (t.x !== null) p.push(ll(t.x, t.y));
    return p;
  }

  // ---- the page's self-check (tests/html) ----------------------------------------------------
  const live = {messages: 0, first_ms: null, per_second: []};
  function selfCheck() {
    const origin = location.protocol === 'file:' ? null : location.origin + '/';
    const foreign = performance.getEntriesByType('resource').map((r) => r.name)
                        .filter((n) => origin === null || !n.startsWith(origin));
    const positions = [...run.drones.values()].filter((d) => d.marker).map((d) => {
      const p = d.marker.getLatLng(), [x_m, y_m] = xy(p);
      return {drone: d.index, name: d.name, x_m, y_m, lat_deg: p.lat, lon_deg: p.lng};
    });
    document.getElementById('swath-check').textContent = JSON.stringify({
      errors: window.swathErrors, foreign_requests: foreign, mode: SWATH_DATA.mode,
      t_s: run.t_s, ended: run.ended, messages: live.messages, per_second: live.per_second,
      drones: run.drones.size, positions: positions, geographic: frame !== null});
  }

  fresh();
  if (SWATH_DATA.mode === 'live') {
    // Every line since the run began (a page opened late catches up), then each as it is written.
    const source = new EventSource('/events');
    source.onmessage = (m) => {
      const now = performance.now();
      if (live.first_ms === null) live.first_ms = now;
      const second = Math.floor((now - live.first_ms) / 1000);
      while (live.per_second.length <= second) live.per_second.push(0);
      ++live.per_second[second];
      ++live.messages;
      apply(JSON.parse(m.data));
      // The run is over: no reconnection (the server may stop at any time from now on).
      if (run.ended) source.close();
    };
    setInterval(() => { draw(); fit(places()); selfCheck(); }, 200);
  } else {
    const events = replayed;
    const end_s = events.length ? events[events.length - 1].t_s : 0;
    const slider = document.getElementById('slider');
    document.getElementById('replay').hidden = false;
    slider.max = end_s;
    let next = 0;
    const seek = (t) => {
      if (t < run.t_s || next === 0) { fresh(); next = 0; }
      while (next < events.length && events[next].t_s <= t) apply(events[next++]);
      run.t_s = t;
      run.dirty = true;
      draw();
      slider.value = t;
    };
    // Where the whole run went: the view fitted once, to everything; then the run's end, or the
    // time the address asks for (view.html#t=SECONDS).
    seek(end_s);
    fit(places());
    const asked = /^#t=([0-9]+(\.[0-9]*)?)$/.exec(location.hash);
    if (asked) seek(Math.min(end_s, Number(asked[1])));
    let timer = null;
    const play = document.getElementById('play');
    const stop = () => { clearInterval(timer); timer = null; play.textContent = 'Play'; };
    play.onclick = () => {
      if (timer) return stop();
      if (run.t_s >= end_s) seek(0);
      play.textContent = 'Pause';
      // A run in about 30 s, whatever its length.
      const step_s = Math.max(0.1, end_s / 300);
      timer = setInterval(() => {
        seek(Math.min(end_s, run.t_s + step_s));
        if (run.t_s >= end_s) stop();
      }, 100);
    };
    slider.oninput = () => { stop(); seek(Number(slider.value)); };
    selfCheck();
  }
})();
