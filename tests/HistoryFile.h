// history.csv read back by a test, as columns by name.
#pragma once

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "TestFiles.h"

namespace anode::testing {

struct History {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  // The column's values, row by row; empty when there is no such column.
  std::vector<double> column(const std::string& name) const {
    std::vector<double> c;
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end()) return c;
    for (const std::vector<double>& row : rows) c.push_back(row[at - names.begin()]);
    return c;
  }
};

inline History readHistory(const std::filesystem::path& file) {
  History h;
  std::istringstream in(readFile(file));
  std::string line;
  std::getline(in, line);
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) h.names.push_back(name);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    h.rows.push_back(row);
  }
  return h;
}

}  // namespace anode::testing
