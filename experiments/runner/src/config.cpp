// Parsing and checking an experiment configuration (see config.hpp and docs/experiments.md).

#include "resolve.hpp"

#include <plmap/experiment/cgal_data.hpp>
#include <plmap/experiment/config.hpp>
#include <plmap/experiment/sweep.hpp>
#include <plmap/strategies/point_locator_registry.hpp>
#include <plmap/strategies/simplification/weighted_oracles.hpp>

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace plmap::experiment {

std::string to_string(ReferenceSlope slope) {
  switch (slope) {
    case ReferenceSlope::none: return "none";
    case ReferenceSlope::constant: return "1";
    case ReferenceSlope::log_n: return "log n";
    case ReferenceSlope::sqrt_n: return "sqrt n";
    case ReferenceSlope::n: return "n";
    case ReferenceSlope::n_log_n: return "n log n";
    case ReferenceSlope::n_squared: return "n^2";
  }
  return "none";
}

namespace detail {

const ParameterSpec* find_spec(const std::vector<ParameterSpec>& schema, const std::string& name) {
  for (const auto& s : schema)
    if (s.name == name) return &s;
  return nullptr;
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

void check_value(const std::string& source, const std::string& key, const ParameterSpec& spec,
                 const ParameterValue& value) {
  if (spec.type == ParameterType::integer || spec.type == ParameterType::real) {
    const double x = std::holds_alternative<double>(value) ? std::get<double>(value)
                                                           : double(std::get<std::int64_t>(value));
    if (!std::isfinite(x)) throw ConfigError(source, key, fmt::format("must be a finite number, got {}", x));
    if (spec.min && x < *spec.min)
      throw ConfigError(source, key, fmt::format("must be at least {}, got {}", *spec.min, to_text(value)));
    if (spec.max && x > *spec.max)
      throw ConfigError(source, key, fmt::format("must be at most {}, got {}", *spec.max, to_text(value)));
  }
  if (spec.type == ParameterType::choice) {
    const auto& s = std::get<std::string>(value);
    if (std::find(spec.choices.begin(), spec.choices.end(), s) == spec.choices.end())
      throw ConfigError(source, key,
                        fmt::format("unknown {} \"{}\" (valid: {})", spec.choice_noun, s, join(spec.choices)));
  }
  if (spec.type == ParameterType::text && std::get<std::string>(value).empty())
    throw ConfigError(source, key, "must not be empty");
}

namespace {

/// The config file, with the key's line when it is known.
std::string source_of(const ExperimentConfig& config, const std::string& key) {
  const auto it = config.key_lines.find(key);
  return it == config.key_lines.end() ? config.source_name() : fmt::format("{}:{}", config.source_name(), it->second);
}

std::string key_of(const std::string& prefix, const std::string& name, const KeyNames& names) {
  const auto it = names.find(name);
  return it != names.end() ? it->second : prefix + "." + name;
}

/// Defaults, seeds, `only_when` applicability, bounds and choices.
ParameterSet resolve(const ExperimentConfig& config, const std::string& prefix, const std::string& what,
                     const std::vector<ParameterSpec>& schema, const ParameterSet& given,
                     const KeyNames& names) {
  ParameterSet out;
  for (const ParameterSpec& spec : schema) {
    const std::string key = key_of(prefix, spec.name, names);
    const std::string source = source_of(config, key);
    if (!spec.only_when.empty()) {
      const bool applies =
          out.has(spec.only_when) &&
          std::find(spec.only_when_values.begin(), spec.only_when_values.end(),
                    to_text(out.get(spec.only_when))) != spec.only_when_values.end();
      if (!applies) {
        if (given.has(spec.name))
          throw ConfigError(source, key,
                            fmt::format("not a parameter of {} with {} = \"{}\" (only for {} = {})", what,
                                        spec.only_when, to_text(out.get(spec.only_when)), spec.only_when,
                                        join(spec.only_when_values, " or ")));
        continue;
      }
    }
    if (given.has(spec.name)) {
      check_value(source, key, spec, given.get(spec.name));
      ParameterValue v = given.get(spec.name);
      if (spec.type == ParameterType::real && std::holds_alternative<std::int64_t>(v))
        v = double(std::get<std::int64_t>(v));
      out.set(spec.name, std::move(v));
    } else if (spec.inherits_seed) {
      out.set(spec.name, std::int64_t(config.seed));
    } else if (spec.default_value) {
      out.set(spec.name, *spec.default_value);
    } else {
      throw ConfigError(source, key, fmt::format("missing; {} needs it ({})", what, spec.doc));
    }
  }
  return out;
}

}  // namespace

ParameterSet resolve_input(const ExperimentConfig& config, int index, const ParameterSet& given,
                           const KeyNames& names) {
  const InputConfig& input = config.inputs[index];
  ParameterSet p = resolve(config, input.key, fmt::format("input kind \"{}\"", input.kind),
                           input_schema(input.kind), given, names);
  if (input.kind == "file") {
    std::filesystem::path path = p.text("path");
    if (path.is_relative()) path = config.base_directory / path;
    std::error_code ec;
    const std::string key = key_of(input.key, "path", names);
    if (!std::filesystem::is_regular_file(path, ec))
      throw ConfigError(source_of(config, key), key, fmt::format("file not found: {}", path.string()));
  }
  if (input.kind == "grid" && p.boolean("hole") && p.integer("cells") % 4 != 0)
    throw ConfigError(source_of(config, key_of(input.key, "cells", names)), key_of(input.key, "cells", names),
                      fmt::format("must be a multiple of 4 with hole = true, got {}", p.integer("cells")));
  return p;
}

std::vector<std::string> split_oracles(const std::string& list) {
  std::vector<std::string> specs;
  std::stringstream stream(list);
  for (std::string item; std::getline(stream, item, ',');) {
    const auto first = item.find_first_not_of(" \t"), last = item.find_last_not_of(" \t");
    if (first == std::string::npos) continue;
    specs.push_back(item.substr(first, last + 1 - first));
  }
  return specs;
}

ParameterSet resolve_step(const ExperimentConfig& config, int index, const ParameterSet& given,
                          int dimension, const KeyNames& names) {
  const StepConfig& step = config.pipeline[index];
  const std::string what = fmt::format("step \"{}\"", step.kind);
  ParameterSet p = resolve(config, step.key, what, step_schema(step.kind), given, names);
  if (step.kind == "evaluate") {
    std::string locator = p.text("locator");
    std::vector<std::string> valid;
    auto collect = [&](auto names_span) {
      for (auto n : names_span) valid.emplace_back(n);
    };
    if (dimension == 1) collect(point_locator_names<1>());
    else collect(point_locator_names<2>());
    if (locator == "default") locator = valid.front();
    if (std::find(valid.begin(), valid.end(), locator) == valid.end())
      throw ConfigError(source_of(config, key_of(step.key, "locator", names)), key_of(step.key, "locator", names),
                        fmt::format("point locator \"{}\" does not work on {} (valid: {})", locator,
                                    dimension == 1 ? "curves (d = 1)" : "triangle surfaces (d = 2)", join(valid)));
    p.set("locator", locator);
  }
  static const std::set<std::string> triangles_only = {"simplify", "smooth", "refine", "peer_simplify"};
  if (triangles_only.count(step.kind) && dimension != 2)
    throw ConfigError(source_of(config, step.key + ".step"), step.key + ".step",
                      fmt::format("step \"{}\" works on triangle surfaces (d = 2), not on curves", step.kind));
  if (step.kind == "simplify" || step.kind == "peer_simplify") {
    const std::string key = key_of(step.key, "oracles", names);
    try {
      WeightedOracles oracles;
      for (const auto& spec : split_oracles(p.text("oracles"))) oracles.add_spec(spec);
      if (oracles.empty()) throw Error("name at least one oracle");
    } catch (const Error& e) {
      throw ConfigError(source_of(config, key), key, e.what());
    }
  }
  if (step.kind == "project") {
    const std::string& target = p.text("target");
    const auto it = std::find_if(config.inputs.begin(), config.inputs.end(),
                                 [&](const InputConfig& in) { return in.name == target; });
    if (it == config.inputs.end()) {
      std::vector<std::string> inputs;
      for (const auto& in : config.inputs) inputs.push_back(in.name);
      throw ConfigError(source_of(config, key_of(step.key, "target", names)), key_of(step.key, "target", names),
                        fmt::format("unknown input \"{}\" (inputs: {})", target, join(inputs)));
    }
    if (it->dimension != dimension)
      throw ConfigError(source_of(config, key_of(step.key, "target", names)), key_of(step.key, "target", names),
                        fmt::format("input \"{}\" has dimension {}, the projected input {}", target,
                                    it->dimension, dimension));
  }
  return p;
}

}  // namespace detail

namespace {

using detail::join;

std::string node_type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "nothing";
  }
}

std::string expected_name(ParameterType type) {
  switch (type) {
    case ParameterType::boolean: return "a boolean (true or false)";
    case ParameterType::integer: return "an integer";
    case ParameterType::real: return "a number";
    case ParameterType::text:
    case ParameterType::choice: return "a string";
  }
  return "?";
}

class Parser {
 public:
  explicit Parser(ExperimentConfig& config) : config_(config), source_(config.source_name()) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw ConfigError(source_, key, what);
  }
  [[noreturn]] void fail_at(const toml::node& node, const std::string& key, const std::string& what) const {
    const auto line = node.source().begin.line;
    throw ConfigError(line > 0 ? fmt::format("{}:{}", source_, line) : source_, key, what);
  }

  /// A TOML value as a typed parameter value (type check only).
  ParameterValue convert(const toml::node& node, const ParameterSpec& spec, const std::string& key) const {
    if (node.source().begin.line > 0) config_.key_lines[key] = int(node.source().begin.line);
    switch (spec.type) {
      case ParameterType::boolean:
        if (auto v = node.value_exact<bool>()) return *v;
        break;
      case ParameterType::integer:
        if (auto v = node.value_exact<std::int64_t>()) return *v;
        break;
      case ParameterType::real:
        if (auto v = node.value_exact<double>()) return *v;
        if (auto v = node.value_exact<std::int64_t>()) return double(*v);
        break;
      case ParameterType::text:
      case ParameterType::choice:
        if (auto v = node.value_exact<std::string>()) return *v;
        break;
    }
    fail_at(node, key, fmt::format("expected {}, got {}", expected_name(spec.type), node_type_name(node)));
  }

  std::string string_key(const toml::table& table, const std::string& prefix, const std::string& name,
                         std::optional<std::string> fallback) const {
    const toml::node* node = table.get(name);
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    if (!node) {
      if (fallback) return *fallback;
      fail(key, "missing");
    }
    auto v = node->value_exact<std::string>();
    if (!v) fail_at(*node, key, fmt::format("expected a string, got {}", node_type_name(*node)));
    if (v->empty()) fail_at(*node, key, "must not be empty");
    return *v;
  }

  void reject_unknown_keys(const toml::table& table, const std::string& prefix,
                           const std::vector<std::string>& valid) const {
    for (auto&& [k, node] : table) {
      const std::string name(k.str());
      if (std::find(valid.begin(), valid.end(), name) == valid.end())
        fail_at(node, prefix.empty() ? name : prefix + "." + name,
                fmt::format("unknown key (valid: {})", join(valid)));
    }
  }

  const toml::table& table_or_fail(const toml::node& node, const std::string& key) const {
    if (const auto* t = node.as_table()) return *t;
    fail_at(node, key, fmt::format("expected a table, got {}", node_type_name(node)));
  }

  /// [[name]]: an array of tables (absent: empty).
  std::vector<const toml::table*> array_of_tables(const toml::table& root, const std::string& name) const {
    std::vector<const toml::table*> out;
    const toml::node* node = root.get(name);
    if (!node) return out;
    const auto* array = node->as_array();
    if (!array) fail_at(*node, name, fmt::format("expected an array of tables ([[{}]]), got {}", name, node_type_name(*node)));
    for (std::size_t i = 0; i < array->size(); ++i)
      out.push_back(&table_or_fail(*array->get(i), fmt::format("{}[{}]", name, i)));
    return out;
  }

  void parse(const toml::table& root) {
    reject_unknown_keys(root, "", {"experiment", "inputs", "pipeline", "sweep", "plots"});
    parse_experiment(root);
    parse_inputs(root);
    parse_pipeline(root);
    check_peer_inputs();
    check_peer_simplify_inputs();
    // The pipeline parameters are checked for each dimension the inputs have.
    std::set<int> dimensions;
    for (const auto& in : config_.inputs)
      if (in.run) dimensions.insert(in.dimension);
    for (int dim : dimensions)
      for (int s = 0; s < int(config_.pipeline.size()); ++s)
        detail::resolve_step(config_, s, config_.pipeline[s].given, dim);
    parse_metrics();
    parse_sweep(root);
    // Every combination, checked before anything runs.
    const auto runs = expand_runs(config_);
    parse_plots(root, runs);
  }

 private:
  void parse_experiment(const toml::table& root) {
    const toml::node* node = root.get("experiment");
    if (!node) fail("experiment", "missing: the config needs an [experiment] table with at least a name");
    const toml::table& t = table_or_fail(*node, "experiment");
    reject_unknown_keys(t, "experiment", {"name", "description", "repetitions", "seed", "metrics"});
    config_.name = string_key(t, "experiment", "name", std::nullopt);
    if (const toml::node* d = t.get("description")) {
      auto v = d->value_exact<std::string>();
      if (!v) fail_at(*d, "experiment.description", fmt::format("expected a string, got {}", node_type_name(*d)));
      config_.description = *v;
    }
    ParameterSpec repetitions;
    repetitions.name = "repetitions", repetitions.type = ParameterType::integer;
    repetitions.min = 1, repetitions.max = 1000;
    if (const toml::node* r = t.get("repetitions")) {
      const auto v = convert(*r, repetitions, "experiment.repetitions");
      detail::check_value(source_, "experiment.repetitions", repetitions, v);
      config_.repetitions = int(std::get<std::int64_t>(v));
    }
    ParameterSpec seed;
    seed.name = "seed", seed.type = ParameterType::integer, seed.min = 0, seed.max = 9.0e15;
    if (const toml::node* s = t.get("seed")) {
      const auto v = convert(*s, seed, "experiment.seed");
      detail::check_value(source_, "experiment.seed", seed, v);
      config_.seed = std::uint64_t(std::get<std::int64_t>(v));
    }
    if (const toml::node* m = t.get("metrics")) {
      const auto* array = m->as_array();
      if (!array) fail_at(*m, "experiment.metrics", fmt::format("expected an array of metric names, got {}", node_type_name(*m)));
      if (array->empty()) fail_at(*m, "experiment.metrics", "empty list (leave the key out to record every metric)");
      for (std::size_t i = 0; i < array->size(); ++i) {
        auto v = array->get(i)->value_exact<std::string>();
        if (!v) fail_at(*array->get(i), fmt::format("experiment.metrics[{}]", i),
                        fmt::format("expected a string, got {}", node_type_name(*array->get(i))));
        config_.metrics.push_back(*v);
      }
    }
  }

  void parse_inputs(const toml::table& root) {
    const auto tables = array_of_tables(root, "inputs");
    if (tables.empty()) fail("inputs", "missing: add at least one [[inputs]] table");
    std::map<std::string, int> kind_count;
    for (const auto* t : tables) {
      if (const toml::node* k = t->get("kind"))
        if (auto v = k->value_exact<std::string>()) ++kind_count[*v];
    }
    std::map<std::string, int> kind_seen;
    std::set<std::string> names;
    for (std::size_t i = 0; i < tables.size(); ++i) {
      const toml::table& t = *tables[i];
      InputConfig in;
      in.key = fmt::format("inputs[{}]", i);
      in.kind = string_key(t, in.key, "kind", std::nullopt);
      const std::vector<std::string> kinds(input_kinds().begin(), input_kinds().end());
      if (std::find(kinds.begin(), kinds.end(), in.kind) == kinds.end())
        fail_at(*t.get("kind"), in.key + ".kind", fmt::format("unknown input kind \"{}\" (valid: {})", in.kind, join(kinds)));
      const int repeat = kind_seen[in.kind]++;
      in.name = string_key(t, in.key, "name",
                           kind_count[in.kind] > 1 ? fmt::format("{}{}", in.kind, repeat) : in.kind);
      if (!names.insert(in.name).second)
        fail(in.key + ".name", fmt::format("input name \"{}\" is used twice; names must be unique", in.name));
      if (const toml::node* r = t.get("run")) {
        auto v = r->value_exact<bool>();
        if (!v) fail_at(*r, in.key + ".run", fmt::format("expected a boolean (true or false), got {}", node_type_name(*r)));
        in.run = *v;
      }
      const auto& schema = input_schema(in.kind);
      std::vector<std::string> valid = {"kind", "name", "run"};
      for (const auto& s : schema) valid.push_back(s.name);
      reject_unknown_keys(t, in.key, valid);
      for (const auto& s : schema)
        if (const toml::node* n = t.get(s.name)) in.given.set(s.name, convert(*n, s, in.key + "." + s.name));
      in.dimension = input_kind_dimension(in.kind);
      config_.inputs.push_back(std::move(in));
      auto& stored = config_.inputs.back();
      stored.parameters = detail::resolve_input(config_, int(i), stored.given);
      if (stored.kind == "file") {
        const auto dim = stored.parameters.integer("dimension");
        stored.dimension = dim != 0 ? int(dim)
                                    : (std::filesystem::path(stored.parameters.text("path")).extension() == ".curve" ? 1 : 2);
      }
      if (stored.kind == "cgal" || (stored.kind == "contact-pair" && stored.parameters.has("mesh")))
        check_cgal_mesh(stored);
    }
    if (std::none_of(config_.inputs.begin(), config_.inputs.end(), [](const InputConfig& in) { return in.run; }))
      fail("inputs", "every input has run = false; nothing would run");
  }

  void check_cgal_mesh(const InputConfig& in) const {
    const std::string key = in.key + ".mesh";
    if (cgal_data_location().empty())
      fail(key, "the CGAL data set is missing: install Debian's libcgal-demo package (apt-get install "
                "libcgal-demo) or set PLMAP_CGAL_DATA to its data.tar.gz");
    const auto names = cgal_mesh_names();
    const std::string& mesh = in.parameters.text("mesh");
    if (!std::binary_search(names.begin(), names.end(), mesh)) {
      std::vector<std::string> some(names.begin(), names.begin() + std::min<std::size_t>(names.size(), 12));
      fail(key, fmt::format("no mesh \"{}\" in the CGAL data set {} ({} meshes, e.g. {}, ...)", mesh,
                            cgal_data_location().string(), names.size(), join(some)));
    }
  }

  void parse_pipeline(const toml::table& root) {
    const auto tables = array_of_tables(root, "pipeline");
    if (tables.empty()) fail("pipeline", "missing: add at least one [[pipeline]] step");
    std::set<std::string> names;
    bool have_map = false;
    for (std::size_t i = 0; i < tables.size(); ++i) {
      const toml::table& t = *tables[i];
      StepConfig step;
      step.key = fmt::format("pipeline[{}]", i);
      step.kind = string_key(t, step.key, "step", std::nullopt);
      const std::vector<std::string> kinds(step_kinds().begin(), step_kinds().end());
      if (std::find(kinds.begin(), kinds.end(), step.kind) == kinds.end())
        fail_at(*t.get("step"), step.key + ".step",
                fmt::format("unknown step \"{}\" (valid: {}){}", step.kind, join(kinds),
                            step.kind == "project"        ? "; this build has no plmap::construct"
                            : step.kind == "peer_project" ? "; this build has no experiments/peers benchmark"
                                                          : ""));
      step.name = string_key(t, step.key, "name", step.kind);
      if (step.name == "input" || step.name == "inputs" || step.name.find('.') != std::string::npos)
        fail(step.key + ".name", fmt::format("\"{}\" cannot name a step (reserved or contains a dot)", step.name));
      if (!names.insert(step.name).second)
        fail(step.key + ".name", fmt::format("step name \"{}\" is used twice; give one of the steps another "
                                             "name = \"...\"", step.name));
      if ((step.kind == "evaluate" || step.kind == "check" || step.kind == "smooth" || step.kind == "refine") && !have_map)
        fail(step.key + ".step",
             fmt::format("step \"{}\" needs a map: put a build, project or simplify step before it", step.kind));
      if (step.kind == "build" || step.kind == "project" || step.kind == "simplify") have_map = true;
      const auto& schema = step_schema(step.kind);
      std::vector<std::string> valid = {"step", "name"};
      for (const auto& s : schema) valid.push_back(s.name);
      reject_unknown_keys(t, step.key, valid);
      for (const auto& s : schema)
        if (const toml::node* n = t.get(s.name)) step.given.set(s.name, convert(*n, s, step.key + "." + s.name));
      config_.pipeline.push_back(std::move(step));
    }
  }

  /// peer_simplify hands a mesh file to the benchmark: every input it runs on must be a file or a
  /// CGAL mesh as it is (not simplified by simplify_to).
  void check_peer_simplify_inputs() const {
    const auto step = std::find_if(config_.pipeline.begin(), config_.pipeline.end(),
                                   [](const StepConfig& s) { return s.kind == "peer_simplify"; });
    if (step == config_.pipeline.end()) return;
    for (const auto& in : config_.inputs) {
      if (!in.run) continue;
      if (in.kind != "file" && in.kind != "cgal")
        fail(in.key + ".kind", fmt::format("input \"{}\" is of kind \"{}\", but {} (peer_simplify) runs only on "
                                           "file or cgal inputs (give other inputs run = false)",
                                           in.name, in.kind, step->key));
      if (in.kind == "cgal" && in.parameters.has("simplify_to") && in.parameters.integer("simplify_to") > 0)
        fail(in.key + ".simplify_to", fmt::format("input \"{}\": {} (peer_simplify) reads the mesh file itself, "
                                                  "so simplify_to must be 0", in.name, step->key));
    }
  }

  /// peer_project runs the benchmark's own input pairs, so every input it runs on must be one.
  void check_peer_inputs() const {
    const auto step = std::find_if(config_.pipeline.begin(), config_.pipeline.end(),
                                   [](const StepConfig& s) { return s.kind == "peer_project"; });
    if (step == config_.pipeline.end()) return;
    for (const auto& in : config_.inputs)
      if (in.run && !is_contact_input_kind(in.kind))
        fail(in.key + ".kind", fmt::format("input \"{}\" is of kind \"{}\", but {} (peer_project) runs only on "
                                           "contact-pair or contact-circles inputs (give other inputs run = false)",
                                           in.name, in.kind, step->key));
  }

  void parse_metrics() {
    const auto available = available_metrics(config_);
    std::vector<std::string> names;
    for (const auto& [n, timing] : available) names.push_back(n);
    std::set<std::string> seen;
    for (std::size_t i = 0; i < config_.metrics.size(); ++i) {
      const std::string key = fmt::format("experiment.metrics[{}]", i);
      if (std::find(names.begin(), names.end(), config_.metrics[i]) == names.end())
        fail(key, fmt::format("unknown metric \"{}\" (valid: {})", config_.metrics[i], join(names)));
      if (!seen.insert(config_.metrics[i]).second) fail(key, fmt::format("metric \"{}\" listed twice", config_.metrics[i]));
    }
  }

  /// [sweep] (one table: one group) or [[sweep]] (an array of tables: one group each).
  void parse_sweep(const toml::table& root) {
    const toml::node* node = root.get("sweep");
    if (!node) return;
    if (node->is_table()) return parse_sweep_group(*node->as_table(), "sweep");
    if (!node->is_array())
      fail_at(*node, "sweep", fmt::format("expected a table ([sweep]) or an array of tables ([[sweep]]), got {}",
                                          node_type_name(*node)));
    for (const toml::table* t : array_of_tables(root, "sweep"))
      parse_sweep_group(*t, fmt::format("sweep[{}]", config_.sweeps.size()));
  }

  void parse_sweep_group(const toml::table& t, const std::string& group_key) {
    SweepGroup& group = config_.sweeps.emplace_back();
    group.key = group_key;
    if (const toml::node* list = t.get("inputs")) group.inputs = sweep_group_inputs(*list, fmt::format("{}.inputs", group_key));
    for (auto&& [k, value] : t) {
      if (k.str() == "inputs") continue;
      SweepAxis axis;
      axis.key = std::string(k.str());
      const std::string key = fmt::format("{}.\"{}\"", group_key, axis.key);
      const ParameterSpec* spec = locate_axis(axis, key, value, group.inputs);
      const auto* array = value.as_array();
      if (!array) fail_at(value, key, fmt::format("expected an array of values, got {}", node_type_name(value)));
      if (array->empty()) fail_at(value, key, "empty list; a sweep needs at least one value");
      for (std::size_t i = 0; i < array->size(); ++i)
        axis.values.push_back(convert(*array->get(i), *spec, fmt::format("{}[{}]", key, i)));
      for (const auto& existing : group.axes)
        if (existing.target == axis.target && existing.index == axis.index && existing.parameter == axis.parameter)
          fail_at(value, key, fmt::format("sweeps the same parameter as \"{}\"", existing.key));
      group.axes.push_back(std::move(axis));
    }
  }

  /// A sweep group's `inputs = ["name", ...]`: running inputs, each once.
  std::vector<int> sweep_group_inputs(const toml::node& list, const std::string& key) const {
    const auto* array = list.as_array();
    if (!array || array->empty())
      fail_at(list, key, "expected a non-empty array of input names");
    std::vector<int> indices;
    for (std::size_t i = 0; i < array->size(); ++i) {
      const std::string item_key = fmt::format("{}[{}]", key, i);
      const auto name = array->get(i)->value_exact<std::string>();
      if (!name) fail_at(*array->get(i), item_key, fmt::format("expected an input name, got {}", node_type_name(*array->get(i))));
      const auto in = std::find_if(config_.inputs.begin(), config_.inputs.end(),
                                   [&](const InputConfig& c) { return c.name == *name; });
      if (in == config_.inputs.end()) {
        std::vector<std::string> names;
        for (const auto& c : config_.inputs) names.push_back(c.name);
        fail_at(*array->get(i), item_key, fmt::format("unknown input \"{}\" (inputs: {})", *name, join(names)));
      }
      if (!in->run) fail_at(*array->get(i), item_key, fmt::format("input \"{}\" has run = false", *name));
      const int index = int(in - config_.inputs.begin());
      if (std::find(indices.begin(), indices.end(), index) != indices.end())
        fail_at(*array->get(i), item_key, fmt::format("input \"{}\" is listed twice", *name));
      indices.push_back(index);
    }
    std::sort(indices.begin(), indices.end());  // runs follow the config's order of inputs
    return indices;
  }

  /// Finds what a sweep key changes; returns the parameter's spec.
  /// `group_inputs`: the inputs of the axis's sweep group (empty: every running input).
  const ParameterSpec* locate_axis(SweepAxis& axis, const std::string& key, const toml::node& at,
                                   const std::vector<int>& group_inputs) const {
    auto in_group = [&](int i) {
      return group_inputs.empty() || std::find(group_inputs.begin(), group_inputs.end(), i) != group_inputs.end();
    };
    const std::string& k = axis.key;
    const auto dot = k.rfind('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == k.size())
      fail_at(at, key, "expected \"<step>.<parameter>\", \"input.<parameter>\" or \"inputs.<name>.<parameter>\"");
    const std::string owner = k.substr(0, dot);
    axis.parameter = k.substr(dot + 1);
    if (axis.parameter == "name" || axis.parameter == "kind" || axis.parameter == "step" || axis.parameter == "run")
      fail_at(at, key, fmt::format("\"{}\" cannot be swept", axis.parameter));
    auto unknown_parameter = [&](const std::string& what, const std::vector<ParameterSpec>& schema) {
      std::vector<std::string> valid;
      for (const auto& s : schema) valid.push_back(s.name);
      fail_at(at, key, fmt::format("{} has no parameter \"{}\" (valid: {})", what, axis.parameter, join(valid)));
    };
    if (owner == "input" || owner.starts_with("inputs.")) {
      axis.target = SweepAxis::Target::input;
      const ParameterSpec* spec = nullptr;
      if (owner == "input") {
        axis.index = -1;
        for (int i = 0; i < int(config_.inputs.size()); ++i) {
          const InputConfig& in = config_.inputs[i];
          if (!in.run || !in_group(i)) continue;
          const auto* s = detail::find_spec(input_schema(in.kind), axis.parameter);
          if (!s) unknown_parameter(fmt::format("input \"{}\" (kind {})", in.name, in.kind), input_schema(in.kind));
          if (spec && s->type != spec->type)
            fail_at(at, key, fmt::format("parameter \"{}\" has different types in different inputs; sweep "
                                         "\"inputs.<name>.{}\" instead", axis.parameter, axis.parameter));
          spec = s;
        }
        return spec;
      }
      const std::string name = owner.substr(7);
      for (int i = 0; i < int(config_.inputs.size()); ++i)
        if (config_.inputs[i].name == name) {
          if (!in_group(i)) fail_at(at, key, fmt::format("input \"{}\" is not among the inputs this sweep runs", name));
          axis.index = i;
          const auto& schema = input_schema(config_.inputs[i].kind);
          if (!(spec = detail::find_spec(schema, axis.parameter)))
            unknown_parameter(fmt::format("input \"{}\" (kind {})", name, config_.inputs[i].kind), schema);
          return spec;
        }
      std::vector<std::string> inputs;
      for (const auto& in : config_.inputs) inputs.push_back(in.name);
      fail_at(at, key, fmt::format("unknown input \"{}\" (inputs: {})", name, join(inputs)));
    }
    axis.target = SweepAxis::Target::step;
    for (int i = 0; i < int(config_.pipeline.size()); ++i)
      if (config_.pipeline[i].name == owner) {
        axis.index = i;
        const auto& schema = step_schema(config_.pipeline[i].kind);
        const auto* spec = detail::find_spec(schema, axis.parameter);
        if (!spec) unknown_parameter(fmt::format("step \"{}\"", owner), schema);
        return spec;
      }
    std::vector<std::string> steps;
    for (const auto& s : config_.pipeline) steps.push_back(s.name);
    fail_at(at, key, fmt::format("unknown step \"{}\" (steps: {}; inputs: \"input.<parameter>\")", owner, join(steps)));
  }

  void parse_plots(const toml::table& root, const std::vector<RunSpec>& runs) {
    std::vector<std::string> columns;
    std::set<std::string> seen;
    for (const auto& run : runs)
      for (const auto& [c, v] : run.columns.items())
        if (seen.insert(c).second) columns.push_back(c);
    for (const auto& [m, timing] : available_metrics(config_))
      if (seen.insert(m).second) columns.push_back(m);
    const auto tables = array_of_tables(root, "plots");
    std::set<std::string> names;
    for (std::size_t i = 0; i < tables.size(); ++i) {
      const toml::table& t = *tables[i];
      PlotConfig plot;
      plot.key = fmt::format("plots[{}]", i);
      reject_unknown_keys(t, plot.key, {"name", "x", "y", "group_by", "log_x", "log_y", "reference", "title",
                                        "x_label", "y_label"});
      plot.name = string_key(t, plot.key, "name", fmt::format("plot{}", i));
      if (plot.name.find_first_of("/\\ ") != std::string::npos)
        fail(plot.key + ".name", "must not contain slashes or spaces (it names the image files)");
      if (!names.insert(plot.name).second) fail(plot.key + ".name", fmt::format("plot name \"{}\" is used twice", plot.name));
      auto known_column = [&](const toml::node& node, const std::string& key, const std::string& c) {
        if (std::find(columns.begin(), columns.end(), c) == columns.end())
          fail_at(node, key, fmt::format("unknown column \"{}\" (valid: {})", c, join(columns)));
        return c;
      };
      plot.x = string_key(t, plot.key, "x", std::nullopt);
      plot.x = known_column(*t.get("x"), plot.key + ".x", plot.x);
      plot.y = string_key(t, plot.key, "y", std::nullopt);
      plot.y = known_column(*t.get("y"), plot.key + ".y", plot.y);
      if (const toml::node* g = t.get("group_by")) {
        const std::string key = plot.key + ".group_by";
        if (g->is_string()) {
          plot.group_by.push_back(known_column(*g, key, string_key(t, plot.key, "group_by", std::nullopt)));
        } else if (const auto* array = g->as_array(); array && !array->empty()) {
          for (std::size_t k = 0; k < array->size(); ++k) {
            const std::string item_key = fmt::format("{}[{}]", key, k);
            auto v = array->get(k)->value_exact<std::string>();
            if (!v) fail_at(*array->get(k), item_key, fmt::format("expected a string, got {}", node_type_name(*array->get(k))));
            plot.group_by.push_back(known_column(*array->get(k), item_key, *v));
          }
        } else {
          fail_at(*g, key, fmt::format("expected a column name or a non-empty array of them, got {}", node_type_name(*g)));
        }
      }
      auto flag = [&](const std::string& name) {
        const toml::node* n = t.get(name);
        if (!n) return false;
        auto v = n->value_exact<bool>();
        if (!v) fail_at(*n, plot.key + "." + name, fmt::format("expected a boolean (true or false), got {}", node_type_name(*n)));
        return *v;
      };
      plot.log_x = flag("log_x");
      plot.log_y = flag("log_y");
      const std::vector<ReferenceSlope> slopes = {ReferenceSlope::none,   ReferenceSlope::constant,
                                                  ReferenceSlope::log_n,  ReferenceSlope::sqrt_n,
                                                  ReferenceSlope::n,      ReferenceSlope::n_log_n,
                                                  ReferenceSlope::n_squared};
      auto slope = [&](const toml::node& node, const std::string& key) {
        auto v = node.value_exact<std::string>();
        if (!v) fail_at(node, key, fmt::format("expected a string, got {}", node_type_name(node)));
        std::vector<std::string> slope_names;
        for (auto s : slopes) {
          if (to_string(s) == *v) return s;
          slope_names.push_back(fmt::format("\"{}\"", to_string(s)));
        }
        fail_at(node, key, fmt::format("unknown reference slope \"{}\" (valid: {})", *v, join(slope_names)));
      };
      if (const toml::node* r = t.get("reference")) {
        const std::string key = plot.key + ".reference";
        if (const auto* array = r->as_array()) {
          for (std::size_t k = 0; k < array->size(); ++k)
            plot.references.push_back(slope(*array->get(k), fmt::format("{}[{}]", key, k)));
        } else {
          plot.references.push_back(slope(*r, key));
        }
        std::erase(plot.references, ReferenceSlope::none);
      }
      plot.title = string_key(t, plot.key, "title", config_.name + ": " + plot.y);
      plot.x_label = string_key(t, plot.key, "x_label", plot.x);
      plot.y_label = string_key(t, plot.key, "y_label", plot.y);
      config_.plots.push_back(std::move(plot));
    }
  }

  ExperimentConfig& config_;
  std::string source_;
};

}  // namespace

std::vector<std::pair<std::string, bool>> available_metrics(const ExperimentConfig& config) {
  std::vector<std::pair<std::string, bool>> out;
  for (const auto& m : input_metrics()) out.emplace_back("input." + m.suffix, m.timing);
  for (const auto& step : config.pipeline)
    for (const auto& m : step_metrics(step.kind)) out.emplace_back(step.name + "." + m.suffix, m.timing);
  return out;
}

ExperimentConfig parse_experiment_text(const std::string& text, const std::string& source_name,
                                       const std::filesystem::path& base_directory) {
  ExperimentConfig config;
  config.source = source_name;
  config.text = text;
  config.base_directory = base_directory;
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw ParseError(source_name, fmt::format("{}:{}", where.line, where.column), std::string(e.description()));
  }
  Parser(config).parse(root);
  return config;
}

ExperimentConfig parse_experiment_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("{}: cannot open the experiment config", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  auto base = path.parent_path();
  if (base.empty()) base = ".";
  return parse_experiment_text(text.str(), path.string(), base);
}

}  // namespace plmap::experiment
