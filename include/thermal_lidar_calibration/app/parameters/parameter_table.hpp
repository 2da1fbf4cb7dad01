#pragma once
// The descriptor machinery behind every parameter table: the core keys (core_parameter_table.cpp),
// the person detectors' (detection_parameter_table.cpp), the node-only keys
// (node_parameter_table.cpp) and any table a part adds later. A table is a list of rows; a row knows its key, the struct field
// it fills, its type and allowed range, unit, documentation and section. From the rows come
//   - loading from any ParameterSource (a YAML file, a NodeHandle), leaving absent keys at the
//     struct's default (the member initialisers are the defaults);
//   - per-key validation with one wording for every bad value:
//       parameter 'population_size' = -3: must be an integer in [2, 100000]
//   - the known keys (typo warnings), the effective "key: value" lines (start-up log, result
//     file) and the documentation (config/default.yaml, docs/parameters.md: parameter_docs.hpp).
// Cross-key rules (elite + crossover <= 1, ...) are not rows: the config structs' validate(),
// called from each table's finishLoading() after the per-key reads, checks them.

#include "thermal_lidar_calibration/app/parameters/parameter_source.hpp"
#include "thermal_lidar_calibration/core/parameter_range.hpp"

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace thermal_lidar_calibration {

// A number row whose range its config struct owns: Struct::ranges() (core/parameter_range.hpp),
// the one list the struct's validate() checks too. Rows of keys no config checks give theirs.
struct ConfigRange {};
inline constexpr ConfigRange kConfigRange{};

// What a string key may hold: any string with a documented meaning of "" (optional), or a
// non-empty one (required; `requirement` is the error text for "").
struct TextRule {
  std::string empty_means;
  std::string requirement;
  static TextRule optional(std::string empty_means) { return {std::move(empty_means), ""}; }
  static TextRule required(std::string requirement) { return {"", std::move(requirement)}; }
};

// One key as the documentation shows it (config/default.yaml, README).
struct ParameterDoc {
  std::string key;
  std::string section;       // heading the key is listed under
  std::string default_yaml;  // the default as config/default.yaml writes it
  std::string meaning;       // "what it is, unit; allowed values; note"
};

// Shared by every row type (src/app/parameters/parameter_table.cpp).
std::string formatParameterNumber(double v);
// The value as the user wrote it, for error messages.
std::string parameterValueText(const ParameterSource& source, const std::string& key);
[[noreturn]] void throwBadParameter(const ParameterSource& source, const std::string& key,
                                    const std::string& requirement);

namespace parameter_detail {
// Each returns nullopt when the key is absent and throws std::invalid_argument on a bad value.
std::optional<long long> readInt(const ParameterSource& s, const std::string& key, IntRange r);
std::optional<double> readReal(const ParameterSource& s, const std::string& key, RealRange r);
std::optional<bool> readBool(const ParameterSource& s, const std::string& key);
std::optional<std::string> readText(const ParameterSource& s, const std::string& key,
                                    const TextRule& rule);
// The index of the option named by the value (read as an integer or as a string).
std::optional<std::size_t> readChoice(const ParameterSource& s, const std::string& key,
                                      const std::vector<std::string>& names, bool as_integer,
                                      const std::string& requirement);
std::string allowedInt(IntRange r);
std::string allowedReal(RealRange r);
std::string allowedText(const TextRule& rule);
std::string allowedChoice(const std::vector<std::string>& names);
std::string describeText(const std::string& value, const TextRule& rule);
std::string yamlReal(double v);
std::string yamlText(const std::string& value);
std::string meaningLine(const std::string& doc, const std::string& unit,
                        const std::string& allowed, const std::string& note);
}  // namespace parameter_detail

template <typename Params>
struct ParameterRow {
  std::string key;
  std::string section;
  std::string meaning;
  std::function<void(const ParameterSource&, Params&)> read;  // no-op when the key is absent
  std::function<std::string(const Params&)> describe;         // effective value, for logs
  std::function<std::string(const Params&)> yaml;             // value as YAML
};

template <typename Params, typename Struct>
class ParameterGroup;

// The rows of one parameter struct `Params`, in documentation order.
template <typename Params>
class ParameterTable {
 public:
  // Rows added after this call are listed under `title`.
  void section(std::string title) { section_ = std::move(title); }
  // Rows that fill the fields of the struct `access` returns (a non-capturing lambda).
  template <typename Struct>
  ParameterGroup<Params, Struct> group(Struct& (*access)(Params&)) {
    return ParameterGroup<Params, Struct>(*this, access);
  }
  // Rows that fill top-level fields of Params.
  ParameterGroup<Params, Params> fields() {
    return ParameterGroup<Params, Params>(*this, [](Params& p) -> Params& { return p; });
  }

  void add(ParameterRow<Params> row) {
    for (const auto& r : rows_) {
      if (r.key == row.key) throw std::logic_error("parameter table: duplicate key " + row.key);
    }
    row.section = section_;
    rows_.push_back(std::move(row));
  }

  // Overrides the fields of `params` whose keys `source` has; throws std::invalid_argument
  // naming the key, the value and the allowed range on the first bad value.
  void load(const ParameterSource& source, Params& params) const {
    for (const auto& row : rows_) row.read(source, params);
  }
  std::vector<std::pair<std::string, std::string>> describe(const Params& params) const {
    std::vector<std::pair<std::string, std::string>> out;
    out.reserve(rows_.size());
    for (const auto& row : rows_) out.emplace_back(row.key, row.describe(params));
    return out;
  }
  std::vector<std::string> keys() const {
    std::vector<std::string> out;
    for (const auto& row : rows_) out.push_back(row.key);
    return out;
  }
  // The documentation of every row, defaults taken from a default-constructed Params.
  std::vector<ParameterDoc> docs() const {
    // Default-initialised (the member initialisers run), not `{}`: GCC 12 warns, wrongly, that a
    // std::string member of a value-initialised CoreParameters may be used uninitialised.
    const Params defaults;
    std::vector<ParameterDoc> out;
    for (const auto& row : rows_) {
      out.push_back({row.key, row.section, row.yaml(defaults), row.meaning});
    }
    return out;
  }

 private:
  std::vector<ParameterRow<Params>> rows_;
  std::string section_;
};

// Adds rows for fields of one struct inside Params. Each method is one key:
//   key, &Struct::field, allowed values, [unit,] doc, [note shown after the allowed values].
template <typename Params, typename Struct>
class ParameterGroup {
 public:
  using Access = Struct& (*)(Params&);
  ParameterGroup(ParameterTable<Params>& table, Access access) : table_(table), access_(access) {}

  template <typename Int>
  void integer(const std::string& key, Int Struct::*field, IntRange range, const std::string& unit,
               const std::string& doc, const std::string& note = "") {
    const Access access = access_;
    add(key, parameter_detail::meaningLine(doc, unit, parameter_detail::allowedInt(range), note),
        [=](const ParameterSource& s, Params& p) {
          if (auto v = parameter_detail::readInt(s, key, range)) access(p).*field = static_cast<Int>(*v);
        },
        [=](const Params& p) { return std::to_string(get(access, p, field)); },
        [=](const Params& p) { return std::to_string(get(access, p, field)); });
  }

  void real(const std::string& key, double Struct::*field, RealRange range,
            const std::string& unit, const std::string& doc, const std::string& note = "") {
    const Access access = access_;
    add(key, parameter_detail::meaningLine(doc, unit, parameter_detail::allowedReal(range), note),
        [=](const ParameterSource& s, Params& p) {
          if (auto v = parameter_detail::readReal(s, key, range)) access(p).*field = *v;
        },
        [=](const Params& p) { return formatParameterNumber(get(access, p, field)); },
        [=](const Params& p) { return parameter_detail::yamlReal(get(access, p, field)); });
  }

  // The same with the range from Struct::ranges().
  template <typename Int>
  void integer(const std::string& key, Int Struct::*field, ConfigRange, const std::string& unit,
               const std::string& doc, const std::string& note = "") {
    integer(key, field, Struct::ranges().of(key, field), unit, doc, note);
  }
  void real(const std::string& key, double Struct::*field, ConfigRange, const std::string& unit,
            const std::string& doc, const std::string& note = "") {
    real(key, field, Struct::ranges().of(key, field), unit, doc, note);
  }

  void boolean(const std::string& key, bool Struct::*field, const std::string& doc,
               const std::string& note = "") {
    const Access access = access_;
    const auto text = [=](const Params& p) -> std::string {
      return get(access, p, field) ? "true" : "false";
    };
    add(key, parameter_detail::meaningLine(doc, "", "bool", note),
        [=](const ParameterSource& s, Params& p) {
          if (auto v = parameter_detail::readBool(s, key)) access(p).*field = *v;
        },
        text, text);
  }

  void text(const std::string& key, std::string Struct::*field, const TextRule& rule,
            const std::string& doc, const std::string& note = "") {
    const Access access = access_;
    add(key, parameter_detail::meaningLine(doc, "", parameter_detail::allowedText(rule), note),
        [=](const ParameterSource& s, Params& p) {
          if (auto v = parameter_detail::readText(s, key, rule)) access(p).*field = *v;
        },
        [=](const Params& p) { return parameter_detail::describeText(get(access, p, field), rule); },
        [=](const Params& p) { return parameter_detail::yamlText(get(access, p, field)); });
  }

  // An enum field named by strings (`refine: local`).
  template <typename Enum>
  void choice(const std::string& key, Enum Struct::*field,
              const std::vector<std::pair<std::string, Enum>>& options,
              const std::string& requirement, const std::string& doc,
              const std::string& note = "") {
    addChoice(key, field, options, /*as_integer=*/false, requirement, doc, note);
  }
  // An enum field named by integers (`algorithm: 2`).
  template <typename Enum>
  void integerChoice(const std::string& key, Enum Struct::*field,
                     const std::vector<std::pair<long long, Enum>>& options,
                     const std::string& requirement, const std::string& doc,
                     const std::string& note = "") {
    std::vector<std::pair<std::string, Enum>> named;
    for (const auto& o : options) named.emplace_back(std::to_string(o.first), o.second);
    addChoice(key, field, named, /*as_integer=*/true, requirement, doc, note);
  }

 private:
  // Reading only: the accessor takes a mutable Params but nothing is written through it.
  template <typename T>
  static const T& get(Access access, const Params& p, T Struct::*field) {
    return access(const_cast<Params&>(p)).*field;
  }

  void add(const std::string& key, std::string meaning,
           std::function<void(const ParameterSource&, Params&)> read,
           std::function<std::string(const Params&)> describe,
           std::function<std::string(const Params&)> yaml) {
    table_.add({key, "", std::move(meaning), std::move(read), std::move(describe), std::move(yaml)});
  }

  template <typename Enum>
  void addChoice(const std::string& key, Enum Struct::*field,
                 const std::vector<std::pair<std::string, Enum>>& options, bool as_integer,
                 const std::string& requirement, const std::string& doc, const std::string& note) {
    const Access access = access_;
    std::vector<std::string> names;
    for (const auto& o : options) names.push_back(o.first);
    const auto name = [=](const Params& p) -> std::string {
      for (const auto& o : options) {
        if (o.second == get(access, p, field)) return o.first;
      }
      return "?";
    };
    add(key, parameter_detail::meaningLine(doc, "", parameter_detail::allowedChoice(names), note),
        [=](const ParameterSource& s, Params& p) {
          if (auto i = parameter_detail::readChoice(s, key, names, as_integer, requirement)) {
            access(p).*field = options[*i].second;
          }
        },
        name, name);
  }

  ParameterTable<Params>& table_;
  Access access_;
};

// The scaffold every table shares, written once. A table's .cpp defines two specialisations:
//   template <> ParameterTable<X> makeParameterTable<X>()    its rows
//   template <> void finishLoading<X>(source, X&)            after the rows: the rules across keys
// and its header declares them; then parameterTable<X>(), loadParameters<X>(source) and
// describeParameters(x) work for X.
template <typename Params>
ParameterTable<Params> makeParameterTable();
template <typename Params>
void finishLoading(const ParameterSource& source, Params& params);

// The table of Params, built on first use.
template <typename Params>
const ParameterTable<Params>& parameterTable() {
  static const ParameterTable<Params> table = makeParameterTable<Params>();
  return table;
}

// The defaults (Params' member initialisers) overridden by what `source` has, then the rules
// across keys. Throws std::invalid_argument naming the key, the value and the allowed range:
//   parameter 'population_size' = -3: must be an integer in [2, 100000]
template <typename Params>
Params loadParameters(const ParameterSource& source) {
  Params params;
  parameterTable<Params>().load(source, params);
  finishLoading(source, params);
  return params;
}

// Every key of the table with its effective value (start-up log, result file), in table order.
template <typename Params>
std::vector<std::pair<std::string, std::string>> describeParameters(const Params& params) {
  return parameterTable<Params>().describe(params);
}

}  // namespace thermal_lidar_calibration
