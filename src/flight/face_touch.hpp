#pragma once
// Where a tumbling capsule first touches the scene's real faces (docs/model.md §5.5): not a
// face's unbounded plane, not only what the centre's ray meets, but every triangle within
// the chord's swept reach, its interior, edges and corners alike.
//
// Broad phase: the faces whose boxes meet the box the capsule sweeps over the chord
// (scene::Scene::faces_in_box). Narrow phase: conservative advancement on the exact
// distance between the capsule's core segment and each triangle. Each face gives a time
// the capsule surely cannot reach it before: from its plane (the centre's height above it
// is a quadratic in time, the core's ends swing by at most h about the centre, so a
// second-order lower bound on each end's clearance gives a safe step) and from the exact
// distance over a bound on how fast any point of the capsule moves. The step is the least of
// these, but never less than kMinFaceStep of motion, so a step may end overlapping a face:
// it is then brought back by regula falsi to the first instant the capsule is within
// kFaceTolerance of it. A face the capsule already touches at the search's start and is
// leaving (its touching point moves away from it: the bounce just resolved) is no touch
// until that point moves into it again; it is stepped past with a plane bound that lets it
// sink at most kLeavingSlack into the face first (counted again from where it is when it is
// spent; the slack does not bound what that adds up to over a long pressed contact, so the
// search gives up past kDeepestSink, and the audit, `j232 trace --check`, measures what is
// left: docs/validation.md §3 and §4). So the
// capsule does not pass through a face, nor a gap narrower than it is, nor bounce off a face
// that is not there.
#include <array>
#include <cstdint>
#include <optional>

#include "projectile/projectile.hpp"
#include "scene/scene.hpp"
#include "strike/contact_search.hpp"

namespace j232::flight {

using Vec3 = Eigen::Vector3d;

inline constexpr double kFaceTolerance = 2e-6;  // m: a capsule this close to a face touches it
inline constexpr double kMinFaceStep = 2e-4;    // m: the least motion of a step (under a tenth of a nail's diameter)
inline constexpr double kLeavingSlack = 1e-5;   // m: how far a face being left may be entered before its touch counts
inline constexpr double kEmbedded = 5e-5;      // m: a capsule deeper in a face at a search's start was put there (a field's embedded stone) or sank there by renewed slacks
inline constexpr double kApproachSpeed = 1e-9;  // m/s: a touching point moving into a face faster than this approaches it
inline constexpr int kMaxFaceSearchSteps = 200000;
// How deep renewed slacks may let a capsule into a face nothing starts pressed into (the deck's
// steel, a flap, a test's turf) before the search gives up on the contact: a face being left is
// entered by kLeavingSlack before its touch counts, counted again from where the capsule is
// each time it is spent, so a sustained pressed contact could sink on without end (a flap has
// no thickness). Deeper than this, with the slack on top, would be deeper than the 0.1 mm the
// audit allows (`j232 trace --check`, kAuditOverlap): the nail is cut off instead
// (CutOff::SankIntoFace, counted and named, never silent). Not the board (a target: its touch
// ends the flight); in a field, whose objects may start pressed into a face, counted below the
// depth they started at (FaceFilter::start_depths). docs/validation.md §3 has the depths the
// shipped runs reach.
inline constexpr double kDeepestSink = 1e-4 - kLeavingSlack;

// The closest points of the segment p0-p1 and the triangle (corner a, edges e1, e2): on the
// segment and on the triangle, and their distance (0 where they cross). Exact: the least
// of the segment's ends against the triangle and the segment against each edge, unless
// the segment crosses the triangle.
struct SegmentTriangle {  // (no initialisers: the search keeps hundreds of them uninitialised until used)
  Vec3 on_segment, on_triangle;
  double distance;
};
// (`gram`: the triangle's constants, scene::Scene::face_gram; the same as Gram::of(triangle).)
SegmentTriangle segment_triangle(const Vec3& p0, const Vec3& p1, const std::array<Vec3, 3>& triangle, const scene::Scene::Gram& gram);
inline SegmentTriangle segment_triangle(const Vec3& p0, const Vec3& p1, const std::array<Vec3, 3>& triangle) {
  return segment_triangle(p0, p1, triangle, scene::Scene::Gram::of(triangle));
}

// The same for scene face f, a triangle or a quad (scene::Scene::face_quad): the exact
// closest points of the segment and the face.
SegmentTriangle segment_face(const Vec3& p0, const Vec3& p1, const scene::Scene& scene, std::uint32_t f);

// One point where the capsule touches a face, its touching point moving into it.
struct TouchPoint {
  Vec3 point = Vec3::Zero();   // on the face
  Vec3 normal = Vec3::UnitZ(); // unit, from the face toward the capsule's core
  Vec3 arm = Vec3::Zero();     // the capsule's touching point from its centre
  std::uint32_t face = 0;
};

struct FaceTouch {
  double time = 0;
  Vec3 centre = Vec3::Zero(), axis = Vec3::UnitZ();  // the capsule then
  Vec3 point = Vec3::Zero();   // the touch, on the face
  Vec3 normal = Vec3::UnitZ(); // unit, from the face toward the capsule's core (a face's, an edge's or a corner's)
  std::uint32_t face = 0;
  int touching = 1;            // faces the capsule touches then with points moving into them (> 1: a simultaneous contact)
  // Every point touching then and moving in (the first is the touch above): on each such face
  // its closest point, and a core's end within the tolerance of a face elsewhere (a nearly
  // flat rod's two ends on one face). At most kMaxTouchPoints, the rest not kept.
  static constexpr int kMaxTouchPoints = 4;
  std::array<TouchPoint, kMaxTouchPoints> points{};
  int point_count = 0;
};

// What a search tells beyond the touch: steps taken, and whether it gave up (the step cap).
struct FaceSearchStats {
  int steps = 0;
  bool gave_up = false;
  bool sank = false;  // gave up: a face being left entered deeper than kDeepestSink
};

// How deep an object started in the faces it was placed pressed into (a field's stone in the
// soil, under the deck's skirt riding over it, under a draped curtain): each such face's
// kDeepestSink is counted below that depth, as the audit allows such an object as deep as it
// started (docs/validation.md §3). The soil is one medium however it is tiled: a depth in any
// ground face counts for every ground face. Allocation-free: at most kMax faces kept, and past
// that the deepest counts for every face.
struct StartDepths {
  static constexpr int kMax = 8;
  std::array<std::uint32_t, kMax> faces{};
  std::array<double, kMax> depths{};
  int count = 0;
  bool overflow = false;
  double ground = 0;   // m, the deepest in any ground face
  double deepest = 0;  // m, the deepest in any face
  void add(std::uint32_t f, double depth, bool is_ground);
  double of(std::uint32_t f, bool is_ground) const;  // m, how deep it started in face f
};

// Faces the search passes over (a guard's curtain the nail is going through).
struct FaceFilter {
  const scene::Scene* scene = nullptr;
  int ignored_guard = -1;  // faces of this guard (label Guard) are not met
  // A field's object: how deep it started in each face (kDeepestSink is counted below that).
  // Null in a J232 test, whose nails start clear of every face.
  const StartDepths* start_depths = nullptr;
  bool ignores(std::uint32_t f) const;
};

// The first approaching touch of the capsule moving as `m` with any of `faces` (sorted)
// within [from, until]; ties go to the lowest face number.
std::optional<FaceTouch> first_face_touch(const scene::Scene& scene, const std::uint32_t* faces, std::size_t count,
                                          const strike::Motion& m, const projectile::Projectile& nail, double from, double until,
                                          const FaceFilter& filter, FaceSearchStats& stats);

// The box the capsule's core sweeps over [from, until] (the centre's parabola's extent, with
// the core's reach and radius about it): the broad phase's query.
void swept_box(const strike::Motion& m, const projectile::Projectile& nail, double from, double until, Vec3& lo, Vec3& hi);

// The capsule's clearance from face f at its state (centre, axis): distance from the core
// segment less the radius (< 0: overlapping). For tests and the audit's cross-check.
double face_clearance(const scene::Scene& scene, std::uint32_t f, const projectile::Projectile& nail, const Vec3& centre, const Vec3& axis);

}  // namespace j232::flight
