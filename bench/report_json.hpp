// --json FILE: an array with one self-contained object per cell.
#pragma once
#include <string>
#include <vector>

#include "io/json_value.hpp"
#include "result.hpp"

namespace vkfuse::bench {

// The members every cell object has (skipped cells with null measurements);
// the ctest check (check_json.cpp) requires each of them.
const std::vector<std::string>& json_required_fields();

json::Value cell_json(const CellResult& r);

// Writes all cells atomically (a failed write leaves no partial file); throws vkfuse::Error(Io).
void write_json(const std::string& path, const std::vector<CellResult>& results);

}  // namespace vkfuse::bench
