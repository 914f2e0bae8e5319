#include "report/scene_view.hpp"
#include "report/text_safety.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "report/svg_chart.hpp"
#include "scene/scene.hpp"
#include "report/result_files.hpp"

namespace j232::report {

namespace {
using Json = nlohmann::ordered_json;

[[maybe_unused]] std::string hex(int r, int g, int b) { return fmt::format("#{:02x}{:02x}{:02x}", r, g, b); }

// A part of the scene as the legend lists it: the faces of one label, or of one guard.
struct Part {
  std::string name, colour;
  double opacity = 1.0;
  std::vector<std::uint32_t> corners;
};

// The export's colours (scene::label_rgb; the ground paler, so that the mower stands out), a
// flap dark as belting rubber (below), and the board and operator zone see-through so that the
// mower inside shows.
[[maybe_unused]] Part part_for(scene::Surface label) {
  const auto c = scene::label_rgb(label);
  Part part{"?", hex(c[0], c[1], c[2]), 1.0, {}};
  switch (label) {
    case scene::Surface::Ground: part.name = "ground", part.colour = hex(150, 195, 120); break;
    case scene::Surface::Housing: part.name = "deck and skirt"; break;
    case scene::Surface::Deflector: part.name = "deflectors"; break;
    case scene::Surface::Guard: part.name = "guard"; break;
    case scene::Surface::TargetOutside: part.name = "board (outside the operator zone)", part.opacity = 0.35; break;
    case scene::Surface::TargetZone: part.name = "board (operator zone)", part.opacity = 0.75; break;
  }
  return part;
}

// Points as the page reads them: x, y, z one after another, to 0.1 mm.
[[maybe_unused]] Json flat(const std::vector<scene::Vec3>& points) {
  Json xyz = Json::array();
  for (const auto& p : points)
    for (int k = 0; k < 3; ++k) xyz.push_back(std::round(p[k] * 1e4) / 1e4);
  return xyz;
}

// A path's colour by its fate (a colour-blind-safe palette): marks orange, the board reached
// without a mark blue, flights past or short of it light blue and green, kept in the deck grey,
// turned back by a guard purple, cut off black.
[[maybe_unused]] std::string fate_colour(const std::string& fate) {
  static const std::map<std::string, std::string> kColours = {
      {"marked_board", "#d55e00"},          {"marked_below_counted_height", "#e69f00"}, {"reached_board_unmarked", "#0072b2"},
      {"over_board", "#56b4e9"},            {"at_rest_short_of_board", "#009e73"},      {"contained_by_housing", "#666666"},
      {"stopped_by_guard", "#cc79a7"},      {"cut_off", "#000000"},                     {"not_struck", "#999999"}};
  const auto it = kColours.find(fate);
  return it == kColours.end() ? "#000000" : it->second;
}

[[maybe_unused]] std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error(fmt::format("cannot read {} (three.js, for the 3D view): reinstall Debian's libjs-three and run scripts/bootstrap again", path));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The scene as the page's script reads it: the points once (to 0.1 mm), each part's
// triangles as indices into them, the lines by group.
[[maybe_unused]] Json scene_data(const scenario::Scenario& s, const scene::Soup& soup, const std::vector<scenario::GuardSpec>& guards,
                const std::vector<scene::Polyline>& lines, const std::vector<ScenePath>& paths) {
  const Json points = flat(soup.points);
  // Parts in label order, each guard its own part (named, and coloured by kind).
  std::map<std::pair<int, int>, Part> parts;
  std::array<std::size_t, scene::kSurfaceKinds> faces{};
  for (std::size_t t = 0; t < soup.triangles.size(); ++t) {
    const scene::Surface label = soup.labels[t];
    ++faces[static_cast<std::size_t>(label)];
    const int guard = label == scene::Surface::Guard ? soup.guard_index[t] : -1;
    auto [it, added] = parts.try_emplace({static_cast<int>(label), guard});
    Part& part = it->second;
    if (added) {
      part = part_for(label);
      if (guard >= 0 && static_cast<std::size_t>(guard) < guards.size()) {
        const auto& g = guards[static_cast<std::size_t>(guard)];
        const bool flap = g.kind == scenario::GuardSpec::Kind::Flap;
        part.name = fmt::format("guard \"{}\" ({})", g.name, flap ? "flap" : "chains");
        if (flap) part.colour = hex(45, 50, 55);
      }
    }
    for (auto v : soup.triangles[t]) part.corners.push_back(v);
  }
  Json out_parts = Json::array();
  for (const auto& [key, part] : parts)
    out_parts.push_back(Json{{"name", part.name},
                             {"label", std::string(scene::name(static_cast<scene::Surface>(key.first)))},
                             {"colour", part.colour},
                             {"opacity", part.opacity},
                             {"triangles", part.corners}});
  Json out_lines = Json::array();
  for (const auto& l : lines)
    out_lines.push_back(
        Json{{"group", l.group}, {"colour", hex(l.colour[0], l.colour[1], l.colour[2])}, {"closed", l.closed}, {"points", flat(l.points)}});
  // Each blade as plates along its arms (the plate's width behind the edge, its
  // thickness) at its height, turned by the page's slider in its own sense.
  Json blades = Json::array();
  for (const auto& sp : s.spindles) {
    Json arms = Json::array();
    for (const auto& arm : sp.blade.arms) arms.push_back(Json{{"azimuth", arm.azimuth}, {"tip", arm.tip_radius()}});
    blades.push_back(Json{{"x", sp.x},
                          {"y", sp.y},
                          {"z", sp.geometry.height},
                          {"sense", sp.sense},
                          {"phase_deg", sp.phase ? *sp.phase / scenario::kDegree : 0.0},
                          {"width", sp.geometry.edge.width},
                          {"thickness", sp.geometry.thickness},
                          {"arms", arms}});
  }
  Json out_paths = Json::array();
  for (const auto& path : paths) {
    Json marks = Json::array();
    for (const auto& [p, kind] : path.marks) {
      Json mark = flat({p});
      mark.push_back(kind);
      marks.push_back(mark);
    }
    out_paths.push_back(Json{
        {"why", path.why}, {"fate", path.fate}, {"colour", fate_colour(path.fate)}, {"points", flat(path.points)}, {"info", path.info}, {"marks", marks}});
  }
  Json face_counts = Json::object();
  for (int l = 0; l < scene::kSurfaceKinds; ++l)
    if (faces[static_cast<std::size_t>(l)]) face_counts[std::string(scene::name(static_cast<scene::Surface>(l)))] = faces[static_cast<std::size_t>(l)];
  return Json{{"title", s.title}, {"units", "m"},       {"faces", face_counts}, {"points", points},
              {"parts", out_parts}, {"lines", out_lines}, {"blades", blades},     {"paths", out_paths}};
}

// The page's own script: builds a mesh per part and a line per polyline, frames the mower,
// lets the legend show and hide them, and writes what it drew into #status (JSON) for a
// test to read.
[[maybe_unused]] constexpr const char* kViewScript = R"JS(
(function () {
  const data = JSON.parse(document.getElementById('scene-data').textContent);
  const status = document.getElementById('status');
  const report = (o) => { status.textContent = JSON.stringify(o); };
  const canvas = document.getElementById('view');
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({canvas: canvas, antialias: true, preserveDrawingBuffer: true});
  } catch (e) {
    document.getElementById('no-webgl').style.display = 'block';
    report({webgl: false, error: String(e)});
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f6f8);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x667755, 0.75));
  const sun = new THREE.DirectionalLight(0xffffff, 0.55);
  sun.position.set(-3, -4, 6);
  scene.add(sun);
  const P = data.points;
  const drawn = {parts: {}, lines: {}};
  const box = new THREE.Box3();
  const legend = document.getElementById('parts');
  const toggle = (name, objects, visible, label, colour) => {
    const row = document.createElement('label');
    if (label) row.dataset.label = label;
    if (colour) row.style.color = colour;
    const box_ = document.createElement('input');
    box_.type = 'checkbox';
    box_.checked = visible;
    box_.addEventListener('change', () => { objects.forEach((o) => { o.visible = box_.checked; }); draw(); });
    objects.forEach((o) => { o.visible = visible; });
    row.appendChild(box_);
    row.appendChild(document.createTextNode(' ' + name));
    legend.appendChild(row);
  };
  data.parts.forEach((part) => {
    const t = part.triangles;
    const xyz = new Float32Array(t.length * 3);
    for (let i = 0; i < t.length; ++i) {
      xyz[3 * i] = P[3 * t[i]]; xyz[3 * i + 1] = P[3 * t[i] + 1]; xyz[3 * i + 2] = P[3 * t[i] + 2];
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    geometry.computeVertexNormals();
    const material = new THREE.MeshLambertMaterial({color: part.colour, side: THREE.DoubleSide,
      transparent: part.opacity < 1, opacity: part.opacity, depthWrite: part.opacity >= 1});
    const mesh = new THREE.Mesh(geometry, material);
    mesh.userData = {label: part.label};
    if (part.opacity < 1) mesh.renderOrder = 1;
    scene.add(mesh);
    if (part.label !== 'ground') { geometry.computeBoundingBox(); box.union(geometry.boundingBox); }
    drawn.parts[part.name] = t.length / 3;
    toggle(part.name + ' (' + (t.length / 3) + ' faces)', [mesh], true, part.label);
  });
  const groups = {};
  data.lines.forEach((line) => {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(line.points), 3));
    const material = new THREE.LineBasicMaterial({color: line.colour});
    const object = line.closed ? new THREE.LineLoop(geometry, material) : new THREE.Line(geometry, material);
    object.renderOrder = 2;
    object.userData = {label: line.group};
    scene.add(object);
    (groups[line.group] = groups[line.group] || []).push(object);
  });
  const names = {tip_circles: 'blade tip circles', feed_stations: 'feed stations', seat: 'seat index point',
                 reach_envelope: 'reach envelope', nail_paths: 'nail paths (run --trajectories)'};
  Object.keys(groups).forEach((g) => {
    drawn.lines[g] = groups[g].length;
    toggle((names[g] || g) + ' (' + groups[g].length + ')', groups[g], true, g);
  });
  // The blades: plates along each arm, turned together by the slider (each in its sense).
  const bladeGroups = [];
  data.blades.forEach((b) => {
    const group = new THREE.Group();
    group.position.set(b.x, b.y, b.z);
    const material = new THREE.MeshLambertMaterial({color: 0x30343a});
    b.arms.forEach((arm) => {
      const plate = new THREE.Mesh(new THREE.BoxBufferGeometry(arm.tip, Math.min(b.width, 0.6 * arm.tip), b.thickness), material);
      plate.position.set(0.5 * arm.tip * Math.cos(arm.azimuth), 0.5 * arm.tip * Math.sin(arm.azimuth), 0);
      plate.rotation.z = arm.azimuth;
      group.add(plate);
    });
    scene.add(group);
    bladeGroups.push({group: group, b: b});
  });
  const turn = (deg) => {
    bladeGroups.forEach((g) => { g.group.rotation.z = g.b.sense * (deg + g.b.phase_deg) * Math.PI / 180; });
  };
  turn(0);
  drawn.blade_plates = data.blades.reduce((n, b) => n + b.arms.length, 0);
  if (bladeGroups.length) {
    drawn.lines.blades = bladeGroups.length;
    toggle('blades (' + bladeGroups.length + ')', bladeGroups.map((g) => g.group), true);
    const slider = document.getElementById('angle');
    slider.addEventListener('input', () => { turn(Number(slider.value)); draw(); });
  } else {
    document.getElementById('angle-row').style.display = 'none';
  }
  // Nail paths kept by the run, coloured by why they were kept, with their marks; a click
  // on one shows its trail.
  const pathObjects = [], byKind = {};
  data.paths.forEach((p, i) => {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(p.points), 3));
    const line = new THREE.Line(geometry, new THREE.LineBasicMaterial({color: p.colour}));
    line.userData = {path: i};
    line.renderOrder = 2;
    const objects = [line];
    p.marks.forEach((m) => {
      const dot = new THREE.Mesh(new THREE.SphereBufferGeometry(0.012, 10, 8),
                                 new THREE.MeshBasicMaterial({color: m[3] === 2 ? 0xd55e00 : 0x0072b2}));
      dot.position.set(m[0], m[1], m[2]);
      drawn.mark_triangles = (drawn.mark_triangles || 0) + dot.geometry.index.count / 3;
      dot.userData = {path: i};
      objects.push(dot);
    });
    objects.forEach((o) => { scene.add(o); pathObjects.push(o); });
    (byKind[p.fate] = byKind[p.fate] || []).push(...objects);
  });
  Object.keys(byKind).forEach((k) => {
    const n = data.paths.filter((p) => p.fate === k).length;
    drawn.lines['paths: ' + k] = n;
    const swatch = '\u25A0 ';
    toggle(swatch + 'nail paths, ' + k.replace(/_/g, ' ') + ' (' + n + ')', byKind[k], true, null,
           data.paths.find((p) => p.fate === k).colour);
  });
  const trail = document.getElementById('trail');
  const ray = new THREE.Raycaster();
  canvas.addEventListener('click', (event) => {
    const r = canvas.getBoundingClientRect();
    const at = new THREE.Vector2(((event.clientX - r.left) / r.width) * 2 - 1, -((event.clientY - r.top) / r.height) * 2 + 1);
    ray.params.Line.threshold = 0.01 * size;
    ray.setFromCamera(at, camera);
    const hit = ray.intersectObjects(pathObjects.filter((o) => o.visible))[0];
    if (!hit) { trail.style.display = 'none'; return; }
    show_trail(hit.object.userData.path);
  });
  function show_trail(i) {
    trail.textContent = data.paths[i].info.join('\n');
    trail.style.display = 'block';
  }
  // #trail=i: path i's trail shown from the start (as a click on it would).
  const start_trail = (location.hash.match(/trail=(\d+)/) || [])[1];
  if (start_trail !== undefined && Number(start_trail) < data.paths.length) show_trail(Number(start_trail));
  // #hide=label,label: parts (by label: ground, housing, guard, target, operator_zone) and
  // line groups hidden from the start.
  const hidden = ((location.hash.match(/hide=([^&]*)/) || [])[1] || '').split(',').filter((x) => x);
  if (hidden.length) {
    scene.traverse((o) => { if (o.userData && hidden.includes(o.userData.label)) o.visible = false; });
    legend.querySelectorAll('label').forEach((row) => {
      if (hidden.includes(row.dataset.label)) row.querySelector('input').checked = false;
    });
  }
  if (box.isEmpty()) box.setFromCenterAndSize(new THREE.Vector3(0, 0, 0), new THREE.Vector3(2, 2, 1));
  const centre = box.getCenter(new THREE.Vector3());
  const size = box.getSize(new THREE.Vector3()).length();
  const camera = new THREE.PerspectiveCamera(40, 1, size / 1000, size * 20);
  camera.up.set(0, 0, 1);  // z is up, as in the scenario
  const controls = new THREE.OrbitControls(camera, canvas);
  controls.target.copy(centre);
  controls.addEventListener('change', () => draw());
  // Views to start from: oblique (from the front left, above), plan (from above), side.
  const views = {oblique: [-0.5, -0.7, 0.45], plan: [0, -0.0001, 1.1], side: [0, -1.1, 0.08]};
  const look = (v) => {
    camera.position.set(centre.x + v[0] * size, centre.y + v[1] * size, centre.z + v[2] * size);
    controls.update();
    draw();
  };
  Object.keys(views).forEach((name) => {
    const button = document.createElement('button');
    button.textContent = name;
    button.addEventListener('click', () => look(views[name]));
    document.getElementById('views').appendChild(button);
  });
  camera.position.set(centre.x + views.oblique[0] * size, centre.y + views.oblique[1] * size, centre.z + views.oblique[2] * size);
  controls.update();
  function draw() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
      renderer.setSize(w, h, false);
      camera.aspect = w / Math.max(h, 1);
      camera.updateProjectionMatrix();
    }
    renderer.render(scene, camera);
  }
  window.addEventListener('resize', draw);
  draw();
  const gl = renderer.getContext();
  report({webgl: true, renderer: String(gl.getParameter(gl.VERSION)), faces: data.faces, parts: drawn.parts, lines: drawn.lines,
          blade_plates: drawn.blade_plates, mark_triangles: drawn.mark_triangles || 0,
          calls: renderer.info.render.calls, triangles: renderer.info.render.triangles});
})();
)JS";
// three.js's licence, kept with the copy inlined into each page.
[[maybe_unused]] constexpr const char* kThreeLicence = R"(/* three.js and its OrbitControls, from Debian's libjs-three, under the MIT licence:
The MIT License

Copyright (c) 2010-2019 three.js authors

Permission is hereby granted, free of charge, to any person obtaining a copy
of this software and associated documentation files (the "Software"), to deal
in the Software without restriction, including without limitation the rights
to use, copy, modify, merge, publish, distribute, sublicense, and/or sell
copies of the Software, and to permit persons to whom the Software is
furnished to do so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in
all copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN
THE SOFTWARE.
*/
)";
}  // namespace

bool scene_view_available() {
#ifdef J232_THREE_JS_DIR
  return true;
#else
  return false;
#endif
}

std::string scene_view_html(const scenario::Scenario& s, const scene::Soup& soup, const std::vector<scenario::GuardSpec>& guards,
                            const std::vector<scene::Polyline>& lines, const std::vector<ScenePath>& paths) {
#ifndef J232_THREE_JS_DIR
  (void)s, (void)soup, (void)guards, (void)lines, (void)paths;
  throw std::runtime_error(
      "this j232 was built without three.js, which the 3D view needs: install Debian's libjs-three (scripts/bootstrap does) and "
      "build again");
#else
  const std::string dir = J232_THREE_JS_DIR;
  const std::string three = read_text(dir + "/three.min.js");
  const std::string orbit = read_text(dir + "/examples/js/controls/OrbitControls.js");
  // The data sits in a JSON script block, made inert there: no name a user gave (a guard's,
  // the title) can close the block or open a comment in it.
  const std::string data = script_safe_json(json_text(scene_data(s, soup, guards, lines, paths), -1));
  std::string page;
  page.reserve(three.size() + orbit.size() + data.size() + 8192);
  page += fmt::format(R"(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{0} — scene in 3D (j232)</title>
<style>
html, body {{ margin: 0; height: 100%; font: 14px/1.4 system-ui, sans-serif; color: #1d2730; }}
#view {{ display: block; width: 100%; height: 100%; }}
#legend {{ position: absolute; top: 10px; left: 10px; max-width: 340px; background: rgba(255,255,255,0.92);
          border: 1px solid #c8d0d8; border-radius: 6px; padding: 10px 12px; }}
#legend h1 {{ font-size: 15px; margin: 0 0 6px; }}
#legend label {{ display: block; white-space: nowrap; }}
#legend p {{ margin: 6px 0 0; color: #4a5a68; font-size: 12px; }}
#views {{ margin-top: 6px; }}
#views button {{ margin-right: 4px; }}
#no-webgl {{ display: none; position: absolute; top: 45%; width: 100%; text-align: center; font-size: 16px; }}
#status {{ display: none; }}
#trail {{ display: none; position: absolute; top: 10px; right: 10px; max-width: 420px; background: rgba(255,255,255,0.95);
         border: 1px solid #c8d0d8; border-radius: 6px; padding: 8px 10px; font-size: 12px; white-space: pre-wrap; }}
</style></head><body>
<canvas id="view"></canvas>
<div id="legend"><h1>{0}</h1><div id="parts"></div><div id="views">View: </div>
<div id="angle-row">Blade angle: <input id="angle" type="range" min="0" max="360" value="0"></div>
<p>Drag to turn, right-drag (or shift-drag) to pan, wheel to zoom; click a nail path for its trail. z is up; lengths in metres.
Written by j232 from {1}.</p></div>
<pre id="trail"></pre>
<div id="no-webgl">This browser could not start WebGL, which the 3D view needs.</div>
<pre id="status">{{}}</pre>
<script type="application/json" id="scene-data">)",
                      escape(s.title), escape(s.file.empty() ? std::string("the scenario") : s.file));
  page += data;
  page += "</script>\n<script>\n";
  page += kThreeLicence;
  page += three;
  page += "\n</script>\n<script>/* three.js OrbitControls (MIT licence) */\n";
  page += orbit;
  page += "\n</script>\n<script>";
  page += kViewScript;
  page += "</script>\n</body></html>\n";
  return page;
#endif
}

}  // namespace j232::report
