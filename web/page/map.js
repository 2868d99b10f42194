// swath's plan page: the files of a plan directory (SWATH_DATA.files, their text as swath wrote
// them) drawn with Leaflet. Everything is read from those files here, so that `swath render DIR
// --html` and `swath plan --html` draw the same page. Positions are [lon, lat] degrees (WGS84) in
// the files and [lat, lon] for Leaflet.
'use strict';
(function () {
  const files = SWATH_DATA.files;
  // The drone colours of coverage.png (apps/swath/coverage_image.cpp).
  const kDroneColours = ['#d92619', '#8c1abf', '#f28c00', '#008c8c', '#8c5919', '#e6339a'];
  const droneColour = (drone) => kDroneColours[(((drone - 1) % 6) + 6) % 6];
  const kArea = '#7fbf5f';
  const kNoFly = '#bf1a0d';

  // Names from the files (flights, drones) as HTML text: tooltips and the panel take HTML.
  const text = (s) => String(s).replace(/[&<>"]/g, (c) => ({'&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;'}[c]));

  // ---- reading the files --------------------------------------------------------------------
  const json = (name) => (files[name] === undefined ? null : JSON.parse(files[name]));
  // RFC 4180 rows (swath quotes a cell only when it holds a comma or a quote).
  function csvRows(text) {
    const rows = [];
    let row = [], cell = '', quoted = false;
    for (let i = 0; i < text.length; ++i) {
      const c = text[i];
      if (quoted) {
        if (c === '"' && text[i + 1] === '"') { cell += '"'; ++i; }
        else if (c === '"') quoted = false;
        else cell += c;
      } else if (c === '"') quoted = true;
      else if (c === ',') { row.push(cell); cell = ''; }
      else if (c === '\n' || c === '\r') {
        if (c === '\r' && text[i + 1] === '\n') ++i;
        row.push(cell); rows.push(row); row = []; cell = '';
      } else cell += c;
    }
    if (cell !== '' || row.length) { row.push(cell); rows.push(row); }
    return rows;
  }
  // CSV as objects keyed by the header's names.
  function csv(name) {
    if (files[name] === undefined) return [];
    const rows = csvRows(files[name]);
    const header = rows.shift() || [];
    return rows.filter((r) => r.length === header.length)
        .map((r) => Object.fromEntries(header.map((h, k) => [h, r[k]])));
  }

  const mission = json('mission.geojson') || {features: []};
  const summary = json('summary.json') || {};
  const photos = csv('photos.csv');
  const waypoints = csv('waypoints.csv');
  const planFiles = Object.keys(files).filter((n) => n.endsWith('.plan')).sort();
  const byRole = (role) => mission.features.filter((f) => f.properties && f.properties.role === role);
  const ll = (p) => [p[1], p[0]];
  const ringLL = (ring) => ring.map(ll);

  // A local east/north frame in metres about the first area vertex: clearances and footprints are
  // a few hundred metres across, where this equirectangular frame is good to well under 0.1 %.
  const origin = (() => {
    const a = byRole('area')[0];
    return a ? a.geometry.coordinates[0][0] : [0, 0];
  })();
  const kEarthRadius_m = 6371008.8;
  const kDegree_rad = Math.PI / 180;
  const cosLat0 = Math.cos(origin[1] * kDegree_rad);
  const toLocal = (lon, lat) => [(lon - origin[0]) * kDegree_rad * kEarthRadius_m * cosLat0,
                                 (lat - origin[1]) * kDegree_rad * kEarthRadius_m];
  const toLatLng = (x, y) => [origin[1] + y / (kDegree_rad * kEarthRadius_m),
                              origin[0] + x / (kDegree_rad * kEarthRadius_m * cosLat0)];

  // ---- geometry -----------------------------------------------------------------------------
  function segmentDistance(p, a, b) {
    const dx = b[0] - a[0], dy = b[1] - a[1];
    const len2 = dx * dx + dy * dy;
    const t = len2 > 0 ? Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2)) : 0;
    return Math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
  }
  function inside(p, ring) {
    let in_ = false;
    for (let i = 0, j = ring.length - 1; i < ring.length; j = i++) {
      const [xi, yi] = ring[i], [xj, yj] = ring[j];
      if ((yi > p[1]) !== (yj > p[1]) && p[0] < ((xj - xi) * (p[1] - yi)) / (yj - yi) + xi) in_ = !in_;
    }
    return in_;
  }
  // Horizontal distance from p to a zone (0 inside it), local metres.
  function zoneDistance(p, ring) {
    if (inside(p, ring)) return 0;
    let d = Infinity;
    for (let i = 0; i + 1 < ring.length; ++i) d = Math.min(d, segmentDistance(p, ring[i], ring[i + 1]));
    return d;
  }
  const signedArea = (ring) => ring.reduce((s, p, i) => {
    const q = ring[(i + 1) % ring.length];
    return s + (p[0] * q[1] - q[0] * p[1]) / 2;
  }, 0);
  const ccw = (ring) => (signedArea(ring) >= 0 ? ring : ring.slice().reverse());
  // The band of width r around a ring: the ring, a rectangle on each edge and a disc on each
  // vertex, all counter-clockwise, filled together with the non-zero rule (their union).
  function bandPieces(ring, r) {
    const pieces = [ccw(ring)];
    for (let i = 0; i + 1 < ring.length; ++i) {
      const [a, b] = [ring[i], ring[i + 1]];
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      if (len === 0) continue;
      const n = [(-(b[1] - a[1]) / len) * r, ((b[0] - a[0]) / len) * r];
      pieces.push(ccw([[a[0] + n[0], a[1] + n[1]], [b[0] + n[0], b[1] + n[1]],
                       [b[0] - n[0], b[1] - n[1]], [a[0] - n[0], a[1] - n[1]]]));
    }
    for (const v of ring) {
      const disc = [];
      for (let k = 0; k < 24; ++k) {
        const t = (2 * Math.PI * k) / 24;
        disc.push([v[0] + r * Math.cos(t), v[1] + r * Math.sin(t)]);
      }
      pieces.push(disc);
    }
    return pieces;
  }
  const localRing = (ring) => ring.map((p) => toLocal(p[0], p[1]));

  // ---- the map ------------------------------------------------------------------------------
  const map = L.map('map', {preferCanvas: true, zoomSnap: 0, attributionControl: false});
  const layers = [];  // {key, label, colour, group, count}
  function layer(key, label, colour, group = L.featureGroup(), count = 0) {
    const entry = {key, label, colour, group, count};
    layers.push(entry);
    return entry;
  }
  // The basemap, first in the list and under every layer: a layer the pilot turns off like any
  // other (the tiles of --basemap-url, or the user's own imagery inlined).
  if (SWATH_DATA.basemap_url)
    layer('basemap', 'Basemap (' + SWATH_DATA.basemap_url.replace(/^https?:\/\/([^/]*).*$/, '$1') + ')',
          '#d8d8d8', L.tileLayer(SWATH_DATA.basemap_url, {maxZoom: 22}), 1);
  // The user's imagery as Web Mercator tiles inlined by zoom level (z/x/y), never fetched: the
  // level nearest the map's zoom is shown, scaled, and past the finest level its tiles scaled up.
  // Each tile is an image overlay between its corners (Leaflet's own tile layer draws nothing in
  // headless Chromium's screenshots, which the tests read).
  const basemap = SWATH_DATA.basemap_tiles;
  const basemapLevels = {};  // zoom -> the level's tiles (a layer group)
  if (basemap) {
    for (const [key, url] of Object.entries(basemap.tiles)) {
      const [z, x, y] = key.split('/').map(Number);
      const n = 2 ** z;
      const lon = (i) => (i / n) * 360 - 180;
      const lat = (j) => Math.atan(Math.sinh(Math.PI * (1 - (2 * j) / n))) / kDegree_rad;
      (basemapLevels[z] ||= L.layerGroup()).addLayer(
          L.imageOverlay(url, [[lat(y + 1), lon(x)], [lat(y), lon(x + 1)]], {pane: 'tilePane', interactive: false}));
    }
    layer('basemap', 'Basemap (your imagery)', '#d8d8d8', L.layerGroup(), Object.keys(basemap.tiles).length);
  }
  let basemapLevel = null;
  function showBasemapLevel() {
    const entry = layers.find((e) => e.key === 'basemap');
    if (!basemap || !entry) return;
    const levels = Object.keys(basemapLevels).map(Number);
    const want = Math.round(map.getZoom());
    const z = levels.reduce((best, l) => (Math.abs(l - want) < Math.abs(best - want) ? l : best), levels[0]);
    if (z === basemapLevel) return;
    if (basemapLevel !== null) entry.group.removeLayer(basemapLevels[basemapLevel]);
    entry.group.addLayer(basemapLevels[z]);
    basemapLevel = z;
  }

  const add = (entry, item) => { item.addTo(entry.group); ++entry.count; return item; };

  // Area and no-fly zones, with the clearance kept from the zones.
  const area = layer('area', 'Area', kArea);
  for (const f of byRole('area'))
    add(area, L.polygon(f.geometry.coordinates.map(ringLL),
                        {color: '#3f6f2f', weight: 1.5, fillColor: kArea, fillOpacity: 0.5}));
  const zones = byRole('no_fly').map((f) => f.geometry.coordinates[0]);
  const noFly = layer('no_fly', 'No-fly zones', kNoFly);
  for (const z of zones)
    add(noFly, L.polygon(ringLL(z), {color: kNoFly, weight: 1.5, fillColor: kNoFly, fillOpacity: 0.35}));
  const flight = summary.flight || {};
  const clearance_m = flight.clearance_m || 0;
  const band = layer('clearance', 'Clearance band' + (clearance_m ? ` (${clearance_m} m)` : ''), '#f2a69f');
  if (clearance_m > 0)
    for (const z of zones) {
      const pieces = bandPieces(localRing(z), clearance_m).map((r) => r.map((p) => toLatLng(p[0], p[1])));
      add(band, L.polygon(pieces, {stroke: false, fillColor: kNoFly, fillOpacity: 0.15, fillRule: 'nonzero'}));
    }
  const regions = layer('regions', 'Drone regions', '#999999');
  for (const f of byRole('region'))
    add(regions, L.polygon(ringLL(f.geometry.coordinates[0]),
                           {color: droneColour(f.properties.drone), weight: 2, fill: false, dashArray: '6 4'}));

  // Photo footprints and points: each footprint along the flight from the photo before or after
  // it on the same line (the sweep's bearing for a line of one photo).
  const footprints = layer('footprints', 'Photo footprints', '#6f8fbf');
  const photoPoints = layer('photos', 'Photo points', '#2f4f8f');
  const camera = summary.camera || {};
  const sweepBearing_rad = ((summary.sweep || {}).bearing_deg || 0) * kDegree_rad;
  const photoLocal = photos.map((p) => toLocal(+p.lon, +p.lat));
  photos.forEach((p, k) => {
    const same = (j) => j >= 0 && j < photos.length && photos[j].flight === p.flight && photos[j].line === p.line;
    const [from, to] = same(k + 1) ? [k, k + 1] : same(k - 1) ? [k - 1, k] : [-1, -1];
    let d = [Math.sin(sweepBearing_rad), Math.cos(sweepBearing_rad)];
    if (from >= 0) {
      const dx = photoLocal[to][0] - photoLocal[from][0], dy = photoLocal[to][1] - photoLocal[from][1];
      if (Math.hypot(dx, dy) > 0) d = [dx / Math.hypot(dx, dy), dy / Math.hypot(dx, dy)];
    }
    const n = [-d[1], d[0]];
    const c = photoLocal[k], h = (camera.footprint_along_m || 0) / 2, w = (camera.footprint_across_m || 0) / 2;
    const corner = (s, t) => toLatLng(c[0] + s * h * d[0] + t * w * n[0], c[1] + s * h * d[1] + t * w * n[1]);
    add(footprints, L.polygon([corner(1, 1), corner(1, -1), corner(-1, -1), corner(-1, 1)],
                              {color: '#6f8fbf', weight: 0.5, fillOpacity: 0.04, interactive: false}));
    add(photoPoints, L.circleMarker([+p.lat, +p.lon],
                                    {radius: 2, stroke: false, fillColor: '#2f4f8f', fillOpacity: 0.9, interactive: false}));
  });

  // Each drone's path in its colour, an arrow on each leg, its first line's start (disc) and its
  // last line's end (square).
  const paths = byRole('path');
  const sweeps = byRole('sweep');
  for (const f of paths) {
    const drone = f.properties.drone, colour = droneColour(drone);
    const entry = layer('path-' + drone, 'Path ' + (f.properties.name || 'drone ' + drone), colour);
    const line = f.geometry.coordinates.map(ll);
    add(entry, L.polyline(line, {color: colour, weight: 2}));
    for (let i = 0; i + 1 < line.length; ++i) {
      const a = toLocal(line[i][1], line[i][0]), b = toLocal(line[i + 1][1], line[i + 1][0]);
      const len = Math.hypot(b[0] - a[0], b[1] - a[1]);
      if (len < 1e-6) continue;
      const d = [(b[0] - a[0]) / len, (b[1] - a[1]) / len], s = Math.min(8, len / 3);
      const tip = [(a[0] + b[0]) / 2 + d[0] * s / 2, (a[1] + b[1]) / 2 + d[1] * s / 2];
      const back = (t) => toLatLng(tip[0] - d[0] * s - d[1] * t * s / 2, tip[1] - d[1] * s + d[0] * t * s / 2);
      L.polygon([toLatLng(tip[0], tip[1]), back(1), back(-1)],
                {color: colour, weight: 1, fillColor: colour, fillOpacity: 1, interactive: false}).addTo(entry.group);
    }
    const own = sweeps.filter((s) => s.properties.drone === drone)
                      .sort((p, q) => p.properties.line - q.properties.line);
    if (own.length) {
      const start = ll(own[0].geometry.coordinates[0]);
      const endAt = own[own.length - 1].geometry.coordinates;
      L.circleMarker(start, {radius: 6, color: '#1a1a1a', weight: 2, fillColor: colour, fillOpacity: 1})
          .bindTooltip('start').addTo(entry.group);
      const e = toLocal(endAt[endAt.length - 1][0], endAt[endAt.length - 1][1]);
      L.polygon([[-5, -5], [5, -5], [5, 5], [-5, 5]].map((o) => toLatLng(e[0] + o[0], e[1] + o[1])),
                {color: '#1a1a1a', weight: 2, fillColor: colour, fillOpacity: 1}).bindTooltip('end').addTo(entry.group);
    }
  }

  // Waypoints: click for the item's number, height and the clearance from the nearest zone.
  const waypointLayer = layer('waypoints', 'Waypoints', '#1a1a1a');
  const zonesLocal = zones.map(localRing);
  const frameName = (summary.terrain || {}).altitude_frame || 'relative';
  const droneOf = Object.fromEntries((summary.drones || []).map((d) => [d.drone, d]));
  const selectors = {};  // 'flight:seq' -> what a click on that waypoint does
  for (const w of waypoints.filter((w) => w.action === 'waypoint')) {
    const colour = droneColour(+w.drone);
    const marker = add(waypointLayer, L.circleMarker([+w.lat, +w.lon],
                                                     {radius: 4, color: colour, weight: 1.5, fillColor: '#ffffff', fillOpacity: 1}));
    const select = () => {
      const p = toLocal(+w.lon, +w.lat);
      const clear = zonesLocal.length ? Math.min(...zonesLocal.map((z) => zoneDistance(p, z))) : null;
      showSelected([['flight', w.flight], ['item', w.seq], [`height (${frameName})`, (+w.alt_m).toFixed(1) + ' m'],
                    ['clearance', clear === null ? 'no no-fly zones' : clear.toFixed(1) + ' m to the nearest no-fly zone'],
                    ['position', (+w.lat).toFixed(7) + ', ' + (+w.lon).toFixed(7)]]);
    };
    marker.on('click', select);
    selectors[w.flight + ':' + w.seq] = select;
  }

  // Where each sortie resumes the drone's work (summary.json), homes (mission.geojson).
  const resume = layer('resume', 'Sortie resume points', '#000000');
  for (const d of summary.drones || [])
    for (const s of d.sorties || [])
      add(resume, L.circleMarker([s.resume.lat_deg, s.resume.lon_deg],
                                 {radius: 5, color: '#000000', weight: 2, fillColor: droneColour(d.drone), fillOpacity: 1})
          .bindTooltip(text(`${d.name}: sortie ${s.sortie} (${s.file}) resumes here`)));
  const homes = layer('homes', 'Homes', '#1a1a1a');
  for (const f of byRole('home')) {
    const colour = f.properties.drone ? droneColour(f.properties.drone) : '#1a1a1a';
    add(homes, L.circleMarker(ll(f.geometry.coordinates), {radius: 7, color: colour, weight: 3, fillColor: '#ffffff', fillOpacity: 1})
        .bindTooltip(text(f.properties.drone ? 'home of ' + (droneOf[f.properties.drone] || {}).name : 'home')));
  }

  // The fences and rally points as each .plan file writes them.
  const fences = layer('fences', 'Fences (.plan)', '#bf8f00');
  const rally = layer('rally', 'Rally points (.plan)', '#bf8f00');
  for (const name of planFiles) {
    const plan = json(name);
    const fence = plan.geoFence || {};
    for (const p of fence.polygons || [])
      add(fences, L.polygon(p.polygon, {color: p.inclusion ? '#bf8f00' : kNoFly, weight: 1.5, dashArray: '4 3', fill: false})
          .bindTooltip(text(`${name}: ${p.inclusion ? 'inclusion' : 'exclusion'} fence`)));
    for (const c of fence.circles || [])
      add(fences, L.circle(c.circle.center, {radius: c.circle.radius, color: c.inclusion ? '#bf8f00' : kNoFly, weight: 1.5, dashArray: '4 3', fill: false})
          .bindTooltip(text(`${name}: ${c.inclusion ? 'inclusion' : 'exclusion'} circle`)));
    for (const r of (plan.rallyPoints || {}).points || [])
      add(rally, L.circleMarker([r[0], r[1]], {radius: 4, color: '#bf8f00', weight: 2, fill: false})
          .bindTooltip(text(name + ': rally point')));
  }

  // ---- the side panel -----------------------------------------------------------------------
  const table = (rows) => '<table>' + rows.map(([k, v]) => `<tr><td>${text(k)}</td><td>${text(v)}</td></tr>`).join('') + '</table>';
  function showSelected(rows) { document.getElementById('selected').innerHTML = table(rows); }
  const minutes = (s) => `${Math.floor(s / 60)} min ${String(Math.round(s % 60)).padStart(2, '0')} s`;
  document.getElementById('title').textContent = SWATH_DATA.title;
  const a = summary.area || {}, cov = summary.coverage || {};
  const rows = [];
  if (a.area_m2 !== undefined) rows.push(['area', `${a.type}, ${(a.area_m2 / 1e4).toFixed(3)} ha`]);
  if (camera.name) rows.push(['camera', `${camera.name}, ${camera.altitude_m} m, GSD ${camera.gsd_cm_per_px} cm/px`]);
  for (const d of summary.drones || [])
    rows.push([d.name, `${(d.path_length_m / 1000).toFixed(2)} km, ${minutes(d.flight_time_s)}, ${d.photos} photos`]);
  if (flight.photos !== undefined) rows.push(['photos', flight.photos]);
  if (cov.covered_fraction !== undefined) rows.push(['coverage', (cov.covered_fraction * 100).toFixed(3) + ' % of the area']);
  if (flight.no_fly_zones)
    rows.push(['clearance', `${flight.min_no_fly_distance_m} m kept from ${flight.no_fly_zones} no-fly zone(s) (asked ${clearance_m} m)`]);
  if (basemap)
    rows.push(['basemap', `zoom ${basemap.min_zoom} to ${basemap.max_zoom}, ${basemap.finest_px_m} m a pixel at the finest ` +
                          `(the raster's: ${basemap.raster_px_m} m${basemap.capped ? '; finer levels left out: the page\'s size budget' : ''})`]);
  if (summary.terrain)
    rows.push(['terrain', `ground ${summary.terrain.ground_min_m} to ${summary.terrain.ground_max_m} m, ${summary.terrain.agl_min_m} to ${summary.terrain.agl_max_m} m above it`]);
  document.getElementById('summary').innerHTML = table(rows);

  // With --terrain: each flight's waypoint heights along its path, in the plan's altitude frame.
  const profiles = {};
  if (summary.terrain) {
    const byFlight = {};
    for (const w of waypoints.filter((w) => w.action === 'waypoint')) (byFlight[w.flight] ||= []).push(w);
    let html = `<h2>Heights along the path (${text(frameName)})</h2>`;
    for (const [flight, ws] of Object.entries(byFlight)) {
      let along_m = 0;
      const points = ws.map((w, k) => {
        if (k > 0) {
          const a = toLocal(+ws[k - 1].lon, +ws[k - 1].lat), b = toLocal(+w.lon, +w.lat);
          along_m += Math.hypot(b[0] - a[0], b[1] - a[1]);
        }
        return [along_m, +w.alt_m];
      });
      const lo = Math.min(...points.map((p) => p[1])), hi = Math.max(...points.map((p) => p[1]));
      const x = (d) => (280 * d) / Math.max(along_m, 1), y = (h) => 70 - (60 * (h - lo)) / Math.max(hi - lo, 1e-9);
      const line = points.map((p) => `${x(p[0]).toFixed(1)},${y(p[1]).toFixed(1)}`).join(' ');
      html += `<div>${text(flight)}: ${lo.toFixed(1)} to ${hi.toFixed(1)} m over ${(along_m / 1000).toFixed(2)} km</div>` +
              `<svg width="280" height="76" data-flight="${text(flight)}" data-points="${points.length}">` +
              `<polyline fill="none" stroke="${droneColour(+ws[0].drone)}" stroke-width="1.5" points="${line}"/></svg>`;
      profiles[flight] = points.length;
    }
    document.getElementById('profiles').innerHTML = html;
  }

  // Layers shown: all but the footprints, or those the address names (#layers=basemap,area,photos).
  // The address flips the boxes as a click would: what it shows is what the pilot's toggle shows.
  const wanted = (/[#&]layers=([^&]*)/.exec(location.hash) || [])[1];
  const shown = wanted === undefined ? null : new Set(wanted.split(',').filter(Boolean));
  const list = document.getElementById('layers');
  for (const entry of layers) {
    if (!entry.count) continue;
    const on = entry.key !== 'footprints';
    if (on) entry.group.addTo(map);
    const label = document.createElement('label');
    label.innerHTML = `<input type="checkbox" data-layer="${entry.key}" ${on ? 'checked' : ''}> <span class="swatch" style="background:${entry.colour}"></span>${text(entry.label)} (${entry.count})`;
    const box = label.querySelector('input');
    box.addEventListener('change', (e) => {
      if (e.target.checked) entry.group.addTo(map); else entry.group.remove();
    });
    list.appendChild(label);
    if (shown && on !== (shown.has(entry.key) || (entry.key.startsWith('path-') && shown.has('paths')))) box.click();
  }

  // A waypoint the address selects, as a click would (#select=drone-1:12): a link to one item.
  const selected = (/[#&]select=([^&]*)/.exec(location.hash) || [])[1];
  if (selected && selectors[decodeURIComponent(selected)]) selectors[decodeURIComponent(selected)]();

  // The view: every feature of mission.geojson, 20 px from the map's edges.
  // Or a zoom level the address asks for (#zoom=17), about that view's centre.
  const all = L.geoJSON(mission);
  const zoom = (/[#&]zoom=([0-9.]+)/.exec(location.hash) || [])[1];
  const fit = () => {
    if (all.getBounds().isValid()) map.fitBounds(all.getBounds(), {padding: [20, 20], animate: false});
    else map.setView([0, 0], 2);
    if (zoom !== undefined) map.setZoom(+zoom, {animate: false});
  };
  fit();
  showBasemapLevel();
  map.on('zoomend', showBasemapLevel);
  // A resized window is fitted again until the pilot moves the map.
  let moved = false;
  for (const what of ['mousedown', 'wheel', 'touchstart', 'keydown'])
    document.getElementById('map').addEventListener(what, () => { moved = true; }, {passive: true});
  map.on('resize', () => { if (!moved) fit(); });

  // What the headless-browser tests read back: script errors, requests made, each layer's count.
  const check = {errors: window.swathErrors, resources: performance.getEntriesByType('resource').map((r) => r.name),
                 layers: Object.fromEntries(layers.map((e) => [e.key, e.count])), profiles,
                 basemap_zoom: basemapLevel,
                 // From the navigation's start: the page read, Leaflet and this script run, then drawn.
                 script_ms: performance.now(), drawn_ms: null};
  const out = document.getElementById('swath-check');
  const record = () => {
    check.resources = performance.getEntriesByType('resource').map((r) => r.name);
    out.textContent = JSON.stringify(check);
  };
  record();
  requestAnimationFrame(() => { check.drawn_ms = performance.now(); record(); });
  // Requests end later (tiles): each one that ends is recorded too.
  new PerformanceObserver(record).observe({type: 'resource', buffered: true});
  window.addEventListener('load', record);
})();
