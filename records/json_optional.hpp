#pragma once
// std::optional in the records' JSON files: an absent value is null in the file, and null reads
// as absent (nlohmann::json 3.11 has no serializer of its own for it).
#include <nlohmann/json.hpp>
#include <optional>

namespace nlohmann {
/// An absent value is null in the file, and null reads as absent.
template <typename T>
struct adl_serializer<std::optional<T>> {
  static void to_json(json& j, const std::optional<T>& v) { j = v ? json(*v) : json(nullptr); }
  static void from_json(const json& j, std::optional<T>& v) {
    if (j.is_null())
      v.reset();
    else
      v = j.get<T>();
  }
};
}  // namespace nlohmann
