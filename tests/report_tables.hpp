#pragma once
// Reads tests/data/report-445-1-tables.csv: the report's lab tables (Table 3.1
// experiment, Table 3.2 theory) in machine-readable form.
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace j232::test {

struct LabRow {
  std::string blade, object;
  double mass_g, mass_lb, v_before_ftmin, e, rpm, contact_in, v_after_theory_ftmin, v_after_experiment_ftmin, v_before_experiment_ftmin;
};

inline std::vector<LabRow> read_lab_rows() {
  const std::string path = std::string(J232_TEST_DATA_DIR) + "/report-445-1-tables.csv";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<LabRow> rows;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    if (f.size() != 11) throw std::runtime_error("bad row in " + path + ": " + line);
    rows.push_back({f[0], f[1], std::stod(f[2]), std::stod(f[3]), std::stod(f[4]), std::stod(f[5]), std::stod(f[6]), std::stod(f[7]),
                    std::stod(f[8]), std::stod(f[9]), std::stod(f[10])});
  }
  return rows;
}

}  // namespace j232::test
