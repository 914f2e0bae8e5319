#include "study/calibration.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

#include "blade/blade_model.hpp"
#include "scenario/csv_reader.hpp"
#include "scenario/input_error.hpp"
#include "scenario/toml_override.hpp"
#include "scenario/toml_reader.hpp"
#include "units/quantity.hpp"

namespace j232::study {

namespace {
using scenario::InputError;

using scenario::require_column;
constexpr auto parse_cell = scenario::quantity_cell;

double t_quantile(int dof) { return boost::math::quantile(boost::math::students_t(static_cast<double>(dof)), 0.975); }

// The impact core for each case, built once.
struct Cases {
  const std::vector<CalibrationCase>& cases;
  std::vector<std::unique_ptr<blade::BladeModel>> models;
  explicit Cases(const std::vector<CalibrationCase>& c) : cases(c) {
    for (const auto& k : c) models.push_back(std::make_unique<blade::BladeModel>(k.input.blade));
  }
  blade::ContactOutcome impact(std::size_t i, const blade::Restitution& r) const {
    return blade::solve_impact(*models[i], cases[i].input.location, cases[i].input.object, r).contact;
  }
  double speed(std::size_t i, const blade::Restitution& r) const { return impact(i, r).velocity_after.norm(); }
};

struct Law {
  LawKind kind;
  double reference_speed;
  blade::Restitution at(const Eigen::VectorXd& p) const {
    return kind == LawKind::Constant ? blade::Restitution::constant(p[0]) : blade::Restitution::power_law(p[0], p[1], 1.0, reference_speed);
  }
  Eigen::VectorXd start() const {
    Eigen::VectorXd p(kind == LawKind::Constant ? 1 : 2);
    p[0] = 0.5;
    if (kind == LawKind::PowerLaw) p[1] = -0.25;
    return p;
  }
  // Keeps parameters where the law is defined: e in [0, 1]; coefficient > 0, exponent <= 0.
  void clamp(Eigen::VectorXd& p) const {
    p[0] = kind == LawKind::Constant ? std::clamp(p[0], 0.0, 1.0) : std::clamp(p[0], 1e-6, 10.0);
    if (kind == LawKind::PowerLaw) p[1] = std::clamp(p[1], -5.0, 0.0);
  }
};

// ln(predicted / measured) over the chosen cases.
Eigen::VectorXd residuals(const Cases& c, const std::vector<std::size_t>& use, const Law& law, const Eigen::VectorXd& p) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(use.size()));
  const blade::Restitution restitution = law.at(p);
  for (std::size_t k = 0; k < use.size(); ++k)
    r[static_cast<Eigen::Index>(k)] = std::log(c.speed(use[k], restitution) / c.cases[use[k]].measured_speed);
  return r;
}

Eigen::MatrixXd jacobian(const Cases& c, const std::vector<std::size_t>& use, const Law& law, const Eigen::VectorXd& p) {
  Eigen::MatrixXd J(static_cast<Eigen::Index>(use.size()), p.size());
  for (Eigen::Index j = 0; j < p.size(); ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(p[j]));
    Eigen::VectorXd up = p, down = p;
    up[j] += h, down[j] -= h;
    J.col(j) = (residuals(c, use, law, up) - residuals(c, use, law, down)) / (2 * h);
  }
  return J;
}

// Levenberg-Marquardt from the law's start, within its bounds.
Eigen::VectorXd fit(const Cases& c, const std::vector<std::size_t>& use, const Law& law) {
  Eigen::VectorXd p = law.start();
  double ssr = residuals(c, use, law, p).squaredNorm();
  double lambda = 1e-3;
  for (int iteration = 0; iteration < 200 && lambda < 1e12; ++iteration) {
    const Eigen::VectorXd r = residuals(c, use, law, p);
    const Eigen::MatrixXd J = jacobian(c, use, law, p);
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    while (!improved && lambda < 1e12) {
      Eigen::MatrixXd damped = A;
      damped.diagonal() += lambda * A.diagonal().cwiseMax(1e-12);
      Eigen::VectorXd next = p - damped.ldlt().solve(g);
      law.clamp(next);
      const double next_ssr = residuals(c, use, law, next).squaredNorm();
      if (next_ssr < ssr) {
        const double step = (next - p).norm();
        p = next, ssr = next_ssr, lambda = std::max(lambda / 10, 1e-12), improved = true;
        if (step < 1e-12 * (1 + p.norm())) return p;
      } else {
        lambda *= 10;
      }
    }
  }
  return p;
}

double rms(const std::vector<CasePrediction>& cases, double CasePrediction::*field) {
  double sum = 0;
  for (const auto& k : cases) sum += std::pow(k.*field / k.measured - 1, 2);
  return std::sqrt(sum / static_cast<double>(cases.size()));
}
}  // namespace

std::vector<CalibrationCase> read_calibration_cases(const std::string& csv_file) {
  const scenario::CsvTable t = scenario::read_csv(csv_file);
  const int name_col = require_column(t, "case", "a name per case");
  const int file_col = require_column(t, "scenario", "an impact case file per row (see scenarios/impact/)");
  const int measured_col = require_column(t, "measured_speed", "the object's measured speed after the impact, e.g. \"2615 ft/min\"");
  const std::filesystem::path folder = std::filesystem::path(csv_file).parent_path();
  std::map<std::string, toml::table> documents;
  std::vector<CalibrationCase> out;
  for (const auto& row : t.rows) {
    CalibrationCase k;
    k.line = row.line;
    k.name = row.fields[static_cast<std::size_t>(name_col)];
    const std::string file = (folder / row.fields[static_cast<std::size_t>(file_col)]).lexically_normal().string();
    try {
      if (!documents.count(file)) documents.emplace(file, scenario::parse_toml_file(file));
      toml::table doc = documents.at(file);
      for (std::size_t c = 0; c < t.header.size(); ++c) {
        const int column = static_cast<int>(c);
        if (column == name_col || column == file_col || column == measured_col || row.fields[c].empty()) continue;
        scenario::set_key(doc, t.header[c], row.fields[c], t.header[c]);
      }
      k.input = scenario::read_impact_case(doc, file);
      blade::BladeModel model(k.input.blade);  // a blade the impact core cannot take is refused here
      (void)blade::solve_impact(model, k.input.location, k.input.object, k.input.restitution);
    } catch (const InputError& e) {
      throw InputError::file_problem(csv_file, row.line, fmt::format("case \"{}\": {}", k.name, e.what()));
    } catch (const std::invalid_argument& e) {
      throw InputError::file_problem(csv_file, row.line, fmt::format("case \"{}\": {}", k.name, e.what()));
    }
    k.measured_speed = parse_cell(t, row, measured_col, units::Kind::Speed);
    if (!(k.measured_speed > 0))
      throw InputError(csv_file, row.line, "measured_speed", row.fields[static_cast<std::size_t>(measured_col)], "a speed above zero");
    out.push_back(std::move(k));
  }
  return out;
}

CalibrationResult calibrate(const std::vector<CalibrationCase>& cases, LawKind kind, const std::string& cases_file) {
  const Cases c(cases);
  const std::size_t n = cases.size();
  const std::size_t parameters = kind == LawKind::Constant ? 1 : 2;
  if (n < parameters + 2)
    throw InputError::file_problem(cases_file, std::nullopt,
                                   fmt::format("{} cases; fitting {} parameter{} with intervals and held-out predictions needs at least {}",
                                               n, parameters, parameters == 1 ? "" : "s", parameters + 2));
  CalibrationResult result;
  result.cases_file = cases_file;
  result.law = kind;
  double log_sum = 0, slowest = HUGE_VAL, fastest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = c.impact(i, cases[i].input.restitution).approach_speed;
    log_sum += std::log(v), slowest = std::min(slowest, v), fastest = std::max(fastest, v);
  }
  if (kind == LawKind::PowerLaw && fastest < 1.5 * slowest)
    throw InputError::file_problem(cases_file, std::nullopt,
                                   fmt::format("the cases' approach speeds span only {:.3g} to {:.3g} m/s: too narrow to fit how e changes "
                                               "with speed (a factor of 1.5 at least); fit a constant e, or add cases at other speeds",
                                               slowest, fastest));
  // The power law's coefficient is e at the cases' typical speed, so the two parameters are
  // nearly independent and the coefficient's interval means something on its own.
  const Law law{kind, std::exp(log_sum / static_cast<double>(n))};
  std::vector<std::size_t> all(n);
  for (std::size_t i = 0; i < n; ++i) all[i] = i;
  const Eigen::VectorXd p = fit(c, all, law);
  result.fitted = law.at(p);
  result.degrees_of_freedom = static_cast<int>(n - parameters);
  const Eigen::VectorXd r = residuals(c, all, law, p);
  const Eigen::MatrixXd J = jacobian(c, all, law, p);
  const double s2 = r.squaredNorm() / result.degrees_of_freedom;
  const Eigen::MatrixXd covariance = s2 * (J.transpose() * J).inverse();
  const double t = t_quantile(result.degrees_of_freedom);
  const char* names[2] = {kind == LawKind::Constant ? "e" : "coefficient", "exponent"};
  for (std::size_t j = 0; j < parameters; ++j) {
    const auto jj = static_cast<Eigen::Index>(j);
    const double se = std::sqrt(std::max(0.0, covariance(jj, jj)));
    result.parameters.push_back({names[j], p[jj], se, p[jj] - t * se, p[jj] + t * se});
  }
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::size_t> others;
    for (std::size_t k = 0; k < n; ++k)
      if (k != i) others.push_back(k);
    CasePrediction pred;
    pred.name = cases[i].name;
    pred.measured = cases[i].measured_speed;
    const auto given = c.impact(i, cases[i].input.restitution);
    pred.approach_speed = given.approach_speed;
    pred.as_given = given.velocity_after.norm();
    const auto fitted = c.impact(i, result.fitted);
    pred.fitted = fitted.velocity_after.norm();
    pred.e_fitted = fitted.e;
    pred.held_out = c.speed(i, law.at(fit(c, others, law)));
    result.cases.push_back(pred);
  }
  result.rms_as_given = rms(result.cases, &CasePrediction::as_given);
  result.rms_fitted = rms(result.cases, &CasePrediction::fitted);
  result.rms_held_out = rms(result.cases, &CasePrediction::held_out);
  return result;
}

std::vector<DropTest> read_drop_tests(const std::string& csv_file) {
  const scenario::CsvTable t = scenario::read_csv(csv_file);
  const int h0 = require_column(t, "drop_height", "the height the object was dropped from, e.g. \"1 m\"");
  const int h1 = require_column(t, "rebound_height", "the height it rebounded to, e.g. \"0.81 m\"");
  std::vector<DropTest> out;
  for (const auto& row : t.rows) {
    DropTest d{parse_cell(t, row, h0, units::Kind::Length), parse_cell(t, row, h1, units::Kind::Length), row.line};
    if (!(d.drop_height > 0))
      throw InputError(csv_file, row.line, "drop_height", row.fields[static_cast<std::size_t>(h0)], "a height above zero");
    if (!(d.rebound_height >= 0 && d.rebound_height <= d.drop_height))
      throw InputError(csv_file, row.line, "rebound_height", row.fields[static_cast<std::size_t>(h1)],
                       "a height from zero to the drop height (nothing rebounds higher than it fell)");
    out.push_back(d);
  }
  if (out.size() < 2)
    throw InputError::file_problem(csv_file, std::nullopt, "one drop; expected at least two (the interval needs their spread)");
  return out;
}

DropTestResult restitution_from_drops(const std::vector<DropTest>& drops) {
  DropTestResult r;
  for (const auto& d : drops) {
    r.e.push_back(std::sqrt(d.rebound_height / d.drop_height));
    r.impact_speed.push_back(std::sqrt(2 * units::standard_gravity * d.drop_height));
  }
  const double n = static_cast<double>(r.e.size());
  for (double e : r.e) r.mean += e / n;
  for (double e : r.e) r.standard_deviation += (e - r.mean) * (e - r.mean) / (n - 1);
  r.standard_deviation = std::sqrt(r.standard_deviation);
  const double half = t_quantile(static_cast<int>(r.e.size()) - 1) * r.standard_deviation / std::sqrt(n);
  r.low = r.mean - half, r.high = r.mean + half;
  return r;
}

}  // namespace j232::study
