// sensor/dataset_manifest.hpp - a Dataset to and from its manifest.json.
#pragma once
#include <string>

#include "io/json_value.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::sensor {

inline constexpr const char* kManifestName = "manifest.json";
inline constexpr const char* kDatasetFormat = "vkfuse-dataset";
inline constexpr int kDatasetVersion = 1;

json::Value manifest_json(const Dataset& dataset);

// s's take of object (background or not), appended when it has none yet.
DatasetTake& take_of(DatasetSensorRecord& s, const std::string& object, bool background);

// Throws Error(Format) "<file>: sensor <serial> listed twice".
void check_unique_serials(const Dataset& d, const std::string& file);

// file names the manifest in messages; every problem is Error(Format)
// "<file>: <where>: <problem>", e.g. "d/manifest.json: sensors[0].width: expected a positive integer".
Dataset dataset_from_json(const json::Value& manifest, const std::string& file, const std::string& directory);

}  // namespace vkfuse::sensor
