// Sobol' indices against functions whose indices are known in closed form.
#include <catch2/catch.hpp>
#include <cmath>

#include "study/sensitivity.hpp"

using namespace j232;

namespace {
constexpr double kPi = 3.14159265358979323846;

std::vector<double> evaluate(const study::SaltelliDesign& d, double (*f)(const std::vector<double>&)) {
  std::vector<double> out;
  for (const auto& x : d.runs()) out.push_back(f(x));
  return out;
}

// Ishigami and Homma (1990), a = 7, b = 0.1, inputs uniform on [-pi, pi].
double ishigami(const std::vector<double>& u) {
  const double x1 = -kPi + 2 * kPi * u[0], x2 = -kPi + 2 * kPi * u[1], x3 = -kPi + 2 * kPi * u[2];
  return std::sin(x1) + 7 * std::sin(x2) * std::sin(x2) + 0.1 * std::pow(x3, 4) * std::sin(x1);
}

// A linear model in four inputs, the fourth ignored: S_i = a_i^2 / sum a^2 (uniform inputs).
double linear(const std::vector<double>& u) { return 1.0 * u[0] + 2.0 * u[1] + 3.0 * u[2] + 0.0 * u[3]; }
}  // namespace

TEST_CASE("sensitivity: Sobol' indices of the Ishigami function", "[sensitivity][statistics]") {
  const auto d = study::saltelli_design(3, 8192);
  const auto s = study::sobol_indices(d, evaluate(d, ishigami), 200, 7);
  // Closed form: V = a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2.
  const double a = 7, b = 0.1, pi4 = std::pow(kPi, 4), pi8 = std::pow(kPi, 8);
  const double v = a * a / 8 + b * pi4 / 5 + b * b * pi8 / 18 + 0.5;
  const double v1 = 0.5 * std::pow(1 + b * pi4 / 5, 2), v2 = a * a / 8, v13 = b * b * pi8 * (1.0 / 18 - 1.0 / 50);
  const double exact_first[] = {v1 / v, v2 / v, 0.0};
  const double exact_total[] = {(v1 + v13) / v, v2 / v, v13 / v};
  CHECK(s.variance == Approx(v).epsilon(0.02));
  for (int i = 0; i < 3; ++i) {
    INFO("input " << i + 1 << ": S " << s.first[i].estimate << " [" << s.first[i].low << ", " << s.first[i].high << "] exact "
                  << exact_first[i] << "; ST " << s.total[i].estimate << " [" << s.total[i].low << ", " << s.total[i].high << "] exact "
                  << exact_total[i]);
    CHECK(s.first[i].estimate == Approx(exact_first[i]).margin(0.03));
    CHECK(s.total[i].estimate == Approx(exact_total[i]).margin(0.03));
    // The bootstrap interval covers the exact value (with a little slack for the estimator's bias).
    CHECK(s.first[i].low - 0.01 <= exact_first[i]);
    CHECK(exact_first[i] <= s.first[i].high + 0.01);
    CHECK(s.total[i].low - 0.01 <= exact_total[i]);
    CHECK(exact_total[i] <= s.total[i].high + 0.01);
  }
}

TEST_CASE("sensitivity: a linear model's indices, and an ignored input's are zero", "[sensitivity][statistics]") {
  const auto d = study::saltelli_design(4, 1024);
  const auto s = study::sobol_indices(d, evaluate(d, linear), 200, 3);
  const double sum = 1 + 4 + 9;
  const double exact[] = {1 / sum, 4 / sum, 9 / sum, 0};
  for (int i = 0; i < 4; ++i) {
    CHECK(s.first[i].estimate == Approx(exact[i]).margin(0.02));
    CHECK(s.total[i].estimate == Approx(exact[i]).margin(0.02));  // additive: no interactions
  }
  CHECK(s.first[3].estimate == 0.0);  // f(AB_4) == f(A) exactly: nothing to attribute
  CHECK(s.total[3].high == 0.0);
  // Deterministic: the same design and outputs give the same indices.
  const auto again = study::sobol_indices(study::saltelli_design(4, 1024), evaluate(d, linear), 200, 3);
  CHECK(again.first[1].low == s.first[1].low);
}
