#include "report/scene_view.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "report/svg_chart.hpp"

namespace j232::report {

namespace {
using Json = nlohmann::ordered_json;

std::string hex(int r, int g, int b) { return fmt::format("#{:02x}{:02x}{:02x}", r, g, b); }

// A part of the scene as the legend lists it: the faces of one label, or of one guard.
struct Part {
  std::string name, colour;
  double opacity = 1.0;
  std::vector<std::uint32_t> corners;
};

// The colours of the PLY export (scene/export.cpp; the ground paler), a flap dark as belting
// rubber, and the board and operator zone see-through so that the mower inside shows.
Part part_for(scene::Surface label) {
  switch (label) {
    case scene::Surface::Ground: return {"ground", hex(150, 195, 120), 1.0, {}};
    case scene::Surface::Housing: return {"deck and skirt", hex(140, 140, 140), 1.0, {}};
    case scene::Surface::Deflector: return {"deflectors", hex(60, 90, 200), 1.0, {}};
    case scene::Surface::Guard: return {"guard", hex(140, 90, 40), 1.0, {}};
    case scene::Surface::TargetOutside: return {"board (outside the operator zone)", hex(235, 235, 225), 0.35, {}};
    case scene::Surface::TargetZone: return {"board (operator zone)", hex(220, 40, 40), 0.75, {}};
  }
  return {"?", hex(0, 0, 0), 1.0, {}};
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error(fmt::format("cannot read {} (three.js, for the 3D view): reinstall Debian's libjs-three and run scripts/bootstrap again", path));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The scene as the page's script reads it: the points once (to 0.1 mm), each part's
// triangles as indices into them, the lines by group.
Json scene_data(const scenario::Scenario& s, const scene::Soup& soup, const std::vector<scenario::GuardSpec>& guards,
                const std::vector<scene::Polyline>& lines) {
  const auto rounded = [](double v) { return std::round(v * 1e4) / 1e4; };
  Json points = Json::array();
  for (const auto& p : soup.points)
    for (int k = 0; k < 3; ++k) points.push_back(rounded(p[k]));
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
  for (const auto& l : lines) {
    Json xyz = Json::array();
    for (const auto& p : l.points)
      for (int k = 0; k < 3; ++k) xyz.push_back(rounded(p[k]));
    out_lines.push_back(Json{{"group", l.group}, {"colour", hex(l.colour[0], l.colour[1], l.colour[2])}, {"closed", l.closed}, {"points", xyz}});
  }
  Json face_counts = Json::object();
  for (int l = 0; l < scene::kSurfaceKinds; ++l)
    if (faces[static_cast<std::size_t>(l)]) face_counts[std::string(scene::name(static_cast<scene::Surface>(l)))] = faces[static_cast<std::size_t>(l)];
  return Json{{"title", s.title}, {"units", "m"}, {"faces", face_counts}, {"points", points}, {"parts", out_parts}, {"lines", out_lines}};
}

// The page's own script: builds a mesh per part and a line per polyline, frames the mower,
// lets the legend show and hide them, and writes what it drew into #status (JSON) for a
// test to read.
constexpr const char* kViewScript = R"JS(
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
  const toggle = (name, objects, visible) => {
    const row = document.createElement('label');
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
    if (part.opacity < 1) mesh.renderOrder = 1;
    scene.add(mesh);
    if (part.label !== 'ground') { geometry.computeBoundingBox(); box.union(geometry.boundingBox); }
    drawn.parts[part.name] = t.length / 3;
    toggle(part.name + ' (' + (t.length / 3) + ' faces)', [mesh], true);
  });
  const groups = {};
  data.lines.forEach((line) => {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(line.points), 3));
    const material = new THREE.LineBasicMaterial({color: line.colour});
    const object = line.closed ? new THREE.LineLoop(geometry, material) : new THREE.Line(geometry, material);
    object.renderOrder = 2;
    scene.add(object);
    (groups[line.group] = groups[line.group] || []).push(object);
  });
  const names = {tip_circles: 'blade tip circles', feed_stations: 'feed stations', seat: 'seat index point',
                 reach_envelope: 'reach envelope', nail_paths: 'nail paths (run --trajectories)'};
  Object.keys(groups).forEach((g) => {
    drawn.lines[g] = groups[g].length;
    toggle((names[g] || g) + ' (' + groups[g].length + ')', groups[g], true);
  });
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
          calls: renderer.info.render.calls, triangles: renderer.info.render.triangles});
})();
)JS";
}  // namespace

bool scene_view_available() {
#ifdef J232_THREE_JS_DIR
  return true;
#else
  return false;
#endif
}

std::string scene_view_html(const scenario::Scenario& s, const scene::Soup& soup, const std::vector<scenario::GuardSpec>& guards,
                            const std::vector<scene::Polyline>& lines) {
#ifndef J232_THREE_JS_DIR
  (void)s, (void)soup, (void)guards, (void)lines;
  throw std::runtime_error(
      "this j232 was built without three.js, which the 3D view needs: install Debian's libjs-three (scripts/bootstrap does) and "
      "build again");
#else
  const std::string dir = J232_THREE_JS_DIR;
  const std::string three = read_text(dir + "/three.min.js");
  const std::string orbit = read_text(dir + "/examples/js/controls/OrbitControls.js");
  // The data sits in a JSON script block: "</" is written "<\/" so that no name a user
  // gave (a guard's, the title) can close the block.
  std::string data = scene_data(s, soup, guards, lines).dump();
  for (std::size_t at = data.find("</"); at != std::string::npos; at = data.find("</", at + 3)) data.replace(at, 2, "<\\/");
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
</style></head><body>
<canvas id="view"></canvas>
<div id="legend"><h1>{0}</h1><div id="parts"></div><div id="views">View: </div>
<p>Drag to turn, right-drag (or shift-drag) to pan, wheel to zoom. z is up; lengths in metres.
Written by <code>j232 scene --html</code> from {1}.</p></div>
<div id="no-webgl">This browser could not start WebGL, which the 3D view needs.</div>
<pre id="status">{{}}</pre>
<script type="application/json" id="scene-data">)",
                      escape(s.title), escape(s.file.empty() ? std::string("the scenario") : s.file));
  page += data;
  page += "</script>\n<script>/* three.js (MIT licence), from Debian's libjs-three */\n";
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
