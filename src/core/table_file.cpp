// Numeric tables as OpenSim storage files or CSV (ptnet/io.hpp).
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {

void write_table_file(const std::string& path, const std::vector<std::string>& columns,
                      const std::vector<std::vector<double>>& rows, const std::string& note, bool force) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext != ".mot" && ext != ".sto" && ext != ".csv")
    throw Error::in(path, "expected a .mot, .sto or .csv file name");
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].size() != columns.size())
      throw Error::in(path, "row " + std::to_string(i) + ": expected " + std::to_string(columns.size()) +
                                " values, found " + std::to_string(rows[i].size()));
  const bool csv = ext == ".csv";
  const char sep = csv ? ',' : '\t';
  std::ostringstream o;
  o << std::setprecision(9);
  if (!csv) {
    o << std::filesystem::path(path).stem().string() << "\nversion=1\nnRows=" << rows.size()
      << "\nnColumns=" << columns.size() << "\ninDegrees=no\n";
    if (!note.empty()) o << note << "\n";
    o << "endheader\n";
  }
  o << join(columns, std::string(1, sep)) << "\n";
  for (const auto& row : rows) {
    for (std::size_t j = 0; j < row.size(); ++j) o << (j ? std::string(1, sep) : "") << row[j];
    o << "\n";
  }
  write_text_file(path, o.str(), force);
}

}  // namespace ptnet
