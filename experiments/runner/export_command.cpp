#include "experiments/runner/export_command.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "core/base/errors.hpp"
#include "core/base/json_reader.hpp"
#include "experiments/runner/command_options.hpp"

namespace closurelab {

namespace {

// The leaves of `v` under `prefix` (objects descend; scalars and strings are leaves; arrays of scalars are
// skipped unless short, which are written as JSON text, e.g. a list of snapshot times).
void flatten(const json& v, const std::string& prefix, std::map<std::string, std::string>& out) {
  if (v.is_object()) {
    for (const auto& [k, x] : v.items()) flatten(x, prefix.empty() ? k : prefix + "." + k, out);
  } else if (v.is_array()) {
    if (v.size() <= 8 && std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_primitive(); }))
      out[prefix] = v.dump();
  } else if (v.is_string()) {
    out[prefix] = v.get<std::string>();
  } else if (!v.is_null()) {
    out[prefix] = v.dump();
  }
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::string table_to_csv(const json& table) {
  if (!table.is_object() || !table.contains("rows") || !table["rows"].is_array())
    throw ConfigError("/rows", "not a closurelab results table (no \"rows\" array)");
  std::vector<std::map<std::string, std::string>> records;
  std::set<std::string> columns;
  for (const json& row : table["rows"]) {
    std::map<std::string, std::string> r;
    for (const char* section : {"params", "errors", "cost"})
      if (row.contains(section)) flatten(row[section], section, r);
    for (const auto& [k, v] : r) columns.insert(k);
    for (const char* key : {"id", "label", "status"})
      if (row.contains(key) && row[key].is_string()) r[key] = row[key].get<std::string>();
    records.push_back(std::move(r));
  }
  std::vector<std::string> order = {"id", "label", "status"};
  order.insert(order.end(), columns.begin(), columns.end());
  std::ostringstream os;
  for (std::size_t c = 0; c < order.size(); ++c) os << (c ? "," : "") << csv_field(order[c]);
  os << "\n";
  for (const auto& r : records) {
    for (std::size_t c = 0; c < order.size(); ++c) {
      const auto it = r.find(order[c]);
      os << (c ? "," : "") << (it == r.end() ? "" : csv_field(it->second));
    }
    os << "\n";
  }
  return os.str();
}

const CommandSpec& export_command_spec() {
  static const CommandSpec spec{
      "export",
      {{"TABLE.json"}},
      "  Writes the table as CSV (to stdout, or FILE): one record per row with id, label, status and every value\n"
      "  of the row's params, errors and cost as a dotted column (errors.vs_averaged_direct_sph.all_nodes.max_rel).",
      {{"--csv", "", "the format: CSV (the one format so far)", false, true},
       {"--out", "FILE", "write the CSV there instead of to stdout"}},
      "  Exit codes: 0 written, 1 a write failed, 2 bad input."};
  return spec;
}

int run_export_command(int argc, char** argv) {
  if (wants_help(export_command_spec(), argc, argv)) {
    std::cout << usage(export_command_spec());
    return 0;
  }
  const ParsedArgs args = parse_command_line(export_command_spec(), argc, argv);
  const std::string table_file = args.positional(0), out_file = args.value("--out");
  std::error_code ec;
  if (!out_file.empty() && std::filesystem::exists(out_file, ec) && std::filesystem::equivalent(table_file, out_file, ec)) {
    std::cerr << "error: --out '" << out_file << "' is the table '" << table_file
              << "' itself: the CSV would overwrite its input; name another file\n";
    return 2;
  }
  const std::string text = table_to_csv(read_table_file_guarded(table_file));  // any size the runner writes
  if (out_file.empty()) {
    std::cout << text;
    if (!std::cout.flush()) {
      std::cerr << "error: cannot write the CSV to stdout\n";
      return 1;
    }
    return 0;
  }
  std::ofstream f(out_file, std::ios::binary);
  f << text;
  f.close();
  if (!f) {
    std::cerr << "error: cannot write '" << out_file << "'\n";
    return 1;
  }
  return 0;
}

}  // namespace closurelab
