// `j232 uq`: how much a scenario's verdict rests on its uncertain inputs.
#include <cstdio>
#include <fmt/format.h>
#include <memory>
#include <unistd.h>

#include "cli/commands.hpp"
#include "cli/exit_codes.hpp"
#include "cli/output_folder.hpp"
#include "report/atomic_file.hpp"
#include "report/text_safety.hpp"
#include "report/uncertainty_report.hpp"
#include "study/uncertainty.hpp"

namespace j232::cli {
namespace {

using report::terminal_safe;

struct UqOptions {
  std::string scenario;
  std::string out = "results/uq";
  int threads = 0;
};

int uq(const UqOptions& o) {
  OutputFolder out(o.out, {"uq.csv", "uq.html", "uq.json"});
  const bool terminal = isatty(fileno(stderr)) != 0;
  const auto r = study::run_uncertainty(o.scenario, o.threads, [&](std::size_t i, std::size_t n) {
    if (terminal) std::fprintf(stderr, "\rassessment %zu of %zu ", i + 1, n);
  });
  if (terminal) std::fprintf(stderr, "\r%40s\r", "");
  const auto j = report::uncertainty_json(r);
  report::write_atomically(out.staged("uq.csv"), report::uncertainty_csv(r));
  report::write_atomically(out.staged("uq.html"), report::uncertainty_html(j));
  report::write_atomically(out.staged("uq.json"), j.dump(2) + "\n");
  out.commit();
  fmt::print("{}\n{} inputs{}, {} assessments of {} replicates\n", terminal_safe(r.title), r.plan.inputs.size(),
             r.plan.defaults ? " (default set of estimated inputs)" : "", r.outputs.size(), r.plan.replicates);
  const auto& p = j["outputs"]["p_pass"];
  fmt::print("P(pass) over the inputs' uncertainty: median {:.3f}, 5-95 % {:.3f} to {:.3f}\n", p["q50"].get<double>(),
             p["q05"].get<double>(), p["q95"].get<double>());
  fmt::print("Robust verdict: {} ({:.1f} % of draws pass)\n", j["robust_verdict"].get<std::string>(),
             100 * j["share_of_draws_passing"].get<double>());
  const auto& s = r.indices[0];
  if (s.variance > 0) {
    fmt::print("What drives P(pass) (total Sobol' index, 95 % interval):\n");
    std::vector<std::size_t> order(r.plan.inputs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return s.total[a].estimate > s.total[b].estimate; });
    for (auto i : order)
      fmt::print("  {:<34} {:.3f} ({:.3f} to {:.3f})\n", terminal_safe(r.plan.inputs[i].parameter), s.total[i].estimate, s.total[i].low,
                 s.total[i].high);
  }
  fmt::print("Wrote {}/uq.html, uq.json and uq.csv\n", terminal_safe(o.out));
  return kOk;
}

}  // namespace

Runner add_uq_command(CLI::App& app) {
  auto o = std::make_shared<UqOptions>();
  CLI::App* cmd = app.add_subcommand("uq", "How much the verdict rests on uncertain inputs: robust verdict and Sobol' sensitivity indices");
  cmd->add_option("scenario", o->scenario, "Scenario file (TOML); its [uncertainty] table, or the default estimated inputs")->required();
  cmd->add_option("--out", o->out, "Output folder for uq.html, uq.json and uq.csv")->capture_default_str();
  cmd->add_option("--threads", o->threads, "Worker threads, 0 = all cores")->check(CLI::Range(0, 1024));
  return [o] { return uq(*o); };
}

}  // namespace j232::cli
