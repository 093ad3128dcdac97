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

// A row's params with the scene's earlier key names as the current ones (the channels' and kolmogorov's eta_over_ly
// is eta_over_l, as the runner reads a stored row), so one column holds the averaging width of every scene.
json params_by_current_names(json params) {
  if (params.is_object() && params.contains("scene") && params["scene"].is_object()) {
    json& scene = params["scene"];
    if (scene.contains("eta_over_ly") && !scene.contains("eta_over_l")) {
      scene["eta_over_l"] = scene["eta_over_ly"];
      scene.erase("eta_over_ly");
    }
  }
  return params;
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
      if (row.contains(section))
        flatten(std::string(section) == "params" ? params_by_current_names(row[section]) : row[section], section, r);
    for (const auto& [k, v] : r) columns.insert(k);
    for (const char* key : {"id", "label", "status", "note"})
      if (row.contains(key) && row[key].is_string()) r[key] = row[key].get<std::string>();
    // The row's error or status message, where it has one (a failed cell's "error", a status's "message").
    for (const char* key : {"error", "message"})
      if (!r.count("message") && row.contains(key) && row[key].is_string()) r["message"] = row[key].get<std::string>();
    if (!r.count("message") && row.contains("reduced_model") && row["reduced_model"].is_object() &&
        row["reduced_model"].contains("message") && row["reduced_model"]["message"].is_string())
      r["message"] = row["reduced_model"]["message"].get<std::string>();
    records.push_back(std::move(r));
  }
  std::vector<std::string> order = {"id", "label", "status"};
  order.insert(order.end(), columns.begin(), columns.end());
  order.insert(order.end(), {"message", "note"});  // the status's why and a warning that leaves it as it is
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

namespace {

// The names and per-node values of a row's coarse data: a 2D row's `fields` (<field>_vx, <field>_vy and the per-node
// lists, node (i, j) at j nx + i) or a column row's `profile` (its lists, one value a node of y); nx = 0 for a
// profile. False when the row has neither (a failed cell).
struct NodeData {
  std::vector<double> x, y;
  std::vector<std::pair<std::string, const json*>> columns;  // name, its flat per-node list
};

bool is_number_list(const json& v, std::size_t size) {
  return v.is_array() && v.size() == size && std::all_of(v.begin(), v.end(), [](const json& e) { return e.is_primitive(); });
}

bool node_data(const json& row, NodeData& d) {
  if (row.contains("fields") && row["fields"].is_object() && row["fields"].contains("x") && row["fields"].contains("y")) {
    const json& f = row["fields"];
    d.x = f["x"].get<std::vector<double>>();
    d.y = f["y"].get<std::vector<double>>();
    const std::size_t nodes = d.x.size() * d.y.size();
    for (const auto& [name, value] : f.items()) {
      if (name == "x" || name == "y") continue;
      if (value.is_object()) {
        for (const auto& [component, list] : value.items())
          if (is_number_list(list, nodes)) d.columns.emplace_back(name + "_" + component, &list);
      } else if (is_number_list(value, nodes)) {
        d.columns.emplace_back(name, &value);
      }
    }
    return true;
  }
  if (row.contains("profile") && row["profile"].is_object() && row["profile"].contains("y")) {
    const json& p = row["profile"];
    d.y = p["y"].get<std::vector<double>>();
    for (const auto& [name, value] : p.items())
      if (name != "y" && is_number_list(value, d.y.size())) d.columns.emplace_back(name, &value);
    return true;
  }
  return false;
}

std::string cell_text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

}  // namespace

std::string table_to_long_csv(const json& table) {
  if (!table.is_object() || !table.contains("rows") || !table["rows"].is_array())
    throw ConfigError("/rows", "not a closurelab results table (no \"rows\" array)");
  std::vector<NodeData> data(table["rows"].size());
  std::vector<bool> has(data.size(), false);
  std::set<std::string> names;
  for (std::size_t r = 0; r < data.size(); ++r) {
    has[r] = node_data(table["rows"][r], data[r]);
    for (const auto& c : data[r].columns) names.insert(c.first);
  }
  std::ostringstream os;
  os << "id,label,i,j,x,y";
  for (const auto& n : names) os << "," << csv_field(n);
  os << "\n";
  for (std::size_t r = 0; r < data.size(); ++r) {
    if (!has[r]) continue;
    const json& row = table["rows"][r];
    const std::string lead = csv_field(row.value("id", "")) + "," + csv_field(row.value("label", ""));
    const NodeData& d = data[r];
    const std::size_t nx = std::max<std::size_t>(d.x.size(), 1);
    for (std::size_t j = 0; j < d.y.size(); ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const std::size_t node = j * nx + i;
        os << lead << "," << (d.x.empty() ? "" : std::to_string(i)) << "," << j << ","
           << (d.x.empty() ? "" : json(d.x[i]).dump()) << "," << json(d.y[j]).dump();
        for (const auto& n : names) {
          os << ",";
          for (const auto& [name, list] : d.columns)
            if (name == n) os << csv_field(cell_text((*list)[node]));
        }
        os << "\n";
      }
  }
  return os.str();
}

const CommandSpec& export_command_spec() {
  static const CommandSpec spec{
      "export",
      {{"TABLE.json"}},
      "  Writes the table as CSV (to stdout, or FILE): one record per row with id, label, status and every value\n"
      "  of the row's params, errors and cost as a dotted column (errors.vs_averaged_direct_sph.all_nodes.max_rel),\n"
      "  then message (the row's error or status message) and note (a warning that leaves the status as it is).\n"
      "  With --long, the rows' coarse profiles and fields instead: one record per coarse node (id, label, i, j, x, y,\n"
      "  then one column per field: reduced_vx, direct_average_vy, ... for a 2D row; reduced, analytic, ... for a\n"
      "  column row's profile, whose i and x are empty).",
      {{"--csv", "", "the format: CSV (the default and the one format; accepted for older command lines)"},
       {"--long", "", "the profiles and fields, one record per coarse node, instead of one record per row"},
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
  const json table = read_table_file_guarded(table_file);  // any size the runner writes
  const std::string text = args.has("--long") ? table_to_long_csv(table) : table_to_csv(table);
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
