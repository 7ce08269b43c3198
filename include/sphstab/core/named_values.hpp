#pragma once
/// Names of enumerated options, written once per enum as a table and read both ways (value -> name for CSVs and
/// summaries, name -> value for the CLI and the Python module), with one form of error for a name not in the table.
///
/// A table lists each value's canonical name first; a later entry for a value already listed is an alias that
/// parsing accepts but names and error messages do not show:
///
///     constexpr NamedValue<LatticeType> kLatticeNames[] = {
///         {LatticeType::Square, "square"}, {LatticeType::Hexagonal, "hex"}, {LatticeType::Hexagonal, "hexagonal"}};
///     name_of(LatticeType::Hexagonal, kLatticeNames)          // "hex"
///     parse_named("hexagonal", kLatticeNames, "lattice")      // LatticeType::Hexagonal
///     parse_named("tri", kLatticeNames, "lattice")            // throws "unknown lattice 'tri' (valid: square, hex)"

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sphstab {

/// One accepted spelling of an enum value.
template <class E>
struct NamedValue {
  E value;
  std::string_view name;
};

namespace named_values_detail {
/// True if entry k of the table is its value's first (canonical) entry.
template <class E, std::size_t N>
constexpr bool is_canonical(const NamedValue<E> (&table)[N], std::size_t k) {
  for (std::size_t j = 0; j < k; ++j)
    if (table[j].value == table[k].value) return false;
  return true;
}
}  // namespace named_values_detail

/// The canonical name of `value`, or "?" for a value the table does not list (a value cast from a bad integer).
template <class E, std::size_t N>
std::string name_of(E value, const NamedValue<E> (&table)[N]) {
  for (const auto& entry : table)
    if (entry.value == value) return std::string(entry.name);
  return "?";
}

/// The canonical names in table order, comma separated (what an error message offers).
template <class E, std::size_t N>
std::string valid_names(const NamedValue<E> (&table)[N]) {
  std::string out;
  for (std::size_t k = 0; k < N; ++k)
    if (named_values_detail::is_canonical(table, k)) (out += out.empty() ? "" : ", ") += table[k].name;
  return out;
}

/// The values in table order, each once.
template <class E, std::size_t N>
std::vector<E> values_of(const NamedValue<E> (&table)[N]) {
  std::vector<E> out;
  for (std::size_t k = 0; k < N; ++k)
    if (named_values_detail::is_canonical(table, k)) out.push_back(table[k].value);
  return out;
}

/// The value named `name` (canonical or alias). Throws std::invalid_argument("unknown <what> '<name>' (valid: ...)").
template <class E, std::size_t N>
E parse_named(std::string_view name, const NamedValue<E> (&table)[N], std::string_view what) {
  for (const auto& entry : table)
    if (entry.name == name) return entry.value;
  throw std::invalid_argument("unknown " + std::string(what) + " '" + std::string(name) +
                              "' (valid: " + valid_names(table) + ")");
}

}  // namespace sphstab
