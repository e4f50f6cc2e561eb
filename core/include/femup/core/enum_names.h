// The names of an enum's values as one table per enum, read both ways: a
// value's name for files, reports and messages, and a name back to its value
// for readers. Each ToString / FromString pair of the library is its table and
// two one-line lookups, so a new value is named in one place.
#pragma once

#include <cstddef>
#include <string_view>

namespace femup {

template <typename Enum>
struct EnumName {
  Enum value;
  const char* name;
};

// The name of `value` in `table`, or `unknown` when the table lacks it.
template <typename Enum, std::size_t N>
constexpr const char* NameIn(const EnumName<Enum> (&table)[N], Enum value,
                             const char* unknown) {
  for (const EnumName<Enum>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return unknown;
}

// Sets *value to the value named `name` in `table` and returns true; false
// (and *value untouched) when no entry has that name.
template <typename Enum, std::size_t N>
bool ValueIn(const EnumName<Enum> (&table)[N], std::string_view name, Enum* value) {
  for (const EnumName<Enum>& entry : table) {
    if (name == entry.name) {
      *value = entry.value;
      return true;
    }
  }
  return false;
}

}  // namespace femup
