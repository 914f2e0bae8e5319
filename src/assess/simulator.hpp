#pragma once
// One nail's life, start to end, as one short function (docs/model.md §5): sample the
// feed, find the strike, resolve the impact, fly. Everything the nails of a scenario
// share (blade model, edges, scene) is built once here; simulate() allocates nothing.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "blade/blade_model.hpp"
#include "blade/impact.hpp"
#include "feed/feed.hpp"
#include "strike/spindle.hpp"
#include "flight/mower.hpp"
#include "flight/nail_flight.hpp"
#include "scenario/scenario.hpp"
#include "scene/j232_setup.hpp"
#include "scene/scene.hpp"

namespace j232::assess {

struct NailOutcome {
  flight::FlightResult flight;  // fate NotStruck when the blade missed it
  double exit_speed = 0;        // m/s as it leaves the blade: after its last contact before it touches anything else (0 if not struck)
  double launch_elevation = 0;  // rad: its velocity's elevation then
  double contact_radius = 0;    // of the first contact, from the spindle's axis, m
  int station = 0;  // the feed station it was dropped at (0-based)
  int spindle = 0;  // the spindle that fed it (0-based)
};

// One nail replayed with its whole trail (`j232 trace`): how it was fed, the feed's strike,
// and every event of its flight.
struct NailReplay {
  NailOutcome outcome;
  feed::NailDrop drop;
  bool struck = false;        // the blade touched it and threw it
  strike::Contact strike;     // the feed's strike (when struck)
  flight::Vec3 falling = flight::Vec3::Zero(), velocity_after = flight::Vec3::Zero(), spin_after = flight::Vec3::Zero();
  std::vector<flight::FlightEvent> events;
  std::vector<flight::FlightStretch> stretches;  // the capsule's motion, stretch by stretch (for an audit)
  std::vector<flight::Vec3> path;
};

class Simulator {
 public:
  // Builds the blade model and the scene; throws scenario::InputError for bad meshes
  // or an unsound blade.
  // `engine` chooses the scene's ray-query index (the same hits either way).
  explicit Simulator(const scenario::Scenario& scenario, scene::Engine engine = scene::default_engine());

  NailOutcome simulate(std::uint64_t replicate, int nail) const;
  // The same nail again (deterministic: the same outcome), its path recorded: the centre at
  // the first strike and at every contact, strike and chord end (for trajectory pictures).
  NailOutcome trace(std::uint64_t replicate, int nail, std::vector<flight::Vec3>& path) const;
  // The same nail again with every event of its flight (deterministic: the same outcome).
  NailReplay replay(std::uint64_t replicate, int nail) const;

  const scenario::Scenario& scenario() const { return scenario_; }
  const scene::Scene& scene() const { return mower_->scene(); }
  double deck_radius() const { return context_.deck_radius; }
  const scene::DeckFootprint& deck_footprint() const { return mower_->footprint(); }
  // How a nail left the deck, in words: "under the skirt", "opening: side discharge",
  // "guard: front chains", "over the deck", "deck edge", "never left the deck".
  std::string exit_name(flight::Exit exit, std::uint16_t index) const;

 private:
  // `path`, `replay`: what to record besides the outcome (null: nothing, as in a run).
  NailOutcome run_nail(std::uint64_t replicate, int nail, std::vector<flight::Vec3>* path, NailReplay* replay = nullptr) const;
  scenario::Scenario scenario_;
  std::vector<strike::Spindle> spindles_;
  std::unique_ptr<flight::Mower> mower_;  // the scene, the flight's settings, the deck
  std::optional<scene::OperatorZone> zone_;  // a derived zone, judged from the throwing blade
  flight::FlightContext context_;
};

}  // namespace j232::assess
