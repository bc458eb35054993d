#pragma once
// Enum <-> name tables: every named choice (back end, accuracy mode,
// acquisition, GL platform, ...) is one constexpr table, and parsing,
// printing and the "expected a, b or c" of an error all read that table.
#include <array>
#include <string>
#include <string_view>

#include "mvr/error.h"

namespace mvr {

template <class E>
struct Named {
  E value;
  const char* name;
};

template <class E, size_t N>
using NameTable = std::array<Named<E>, N>;

// The names joined: separator between them, lastSeparator before the last.
template <class E, size_t N>
std::string joinNames(const NameTable<E, N>& table, const char* separator, const char* lastSeparator) {
  std::string out;
  for (size_t i = 0; i < N; ++i)
    out += (i == 0 ? "" : i + 1 == N ? lastSeparator : separator) + std::string(table[i].name);
  return out;
}

// "a, b or c", for messages.
template <class E, size_t N>
std::string alternatives(const NameTable<E, N>& table) {
  return joinNames(table, ", ", " or ");
}

// "a|b|c", for a help's type column.
template <class E, size_t N>
std::string choices(const NameTable<E, N>& table) {
  return joinNames(table, "|", "|");
}

template <class E, size_t N>
const char* nameOf(const NameTable<E, N>& table, E value) {
  for (const auto& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

// Throws mvr::Error naming `where` (a flag) and what was expected.
template <class E, size_t N>
E parseName(const NameTable<E, N>& table, std::string_view name, const char* where, const char* noun) {
  for (const auto& entry : table)
    if (name == entry.name) return entry.value;
  fail(where, "unknown " + std::string(noun) + " '" + std::string(name) + "' (expected " +
                  alternatives(table) + ")");
}

}  // namespace mvr
