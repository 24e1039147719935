// The reports of a run: the table and summary on stdout, --json, --plot.
#pragma once
#include <cstdio>
#include <string>
#include <vector>

#include "io/json_value.hpp"
#include "result.hpp"

namespace vkfuse::bench {

// The readable table on stdout, printed row by row as cells finish.

void print_table_header(std::FILE* out);
// One line per cell (a skipped cell says why); with --profile a second line of stage times.
void print_row(std::FILE* out, const CellResult& r);
// The workload's peer, once after its cells: its time per sensor and its error.
void print_peer(std::FILE* out, const PeerResult& p);

// The lines after the table: accuracy of the Vulkan cells against docs/spec.md's
// tolerance, and what batching sensors buys.

void print_summary(std::FILE* out, const std::vector<CellResult>& results);

// --json FILE: an array with one self-contained object per cell.

// The members every cell object has (skipped cells with null measurements);
// the ctest check (check_json.cpp) requires each of them.
const std::vector<std::string>& json_required_fields();

json::Value cell_json(const CellResult& r);

// Writes all cells atomically (a failed write leaves no partial file); throws vkfuse::Error(Io).
void write_json(const std::string& path, const std::vector<CellResult>& results);

// --plot FILE.svg: time against error, log-log, one colour per method and one
// marker per backend and precision and per peer (Python, OpenCV C++), so the
// speed/accuracy trade-off is seen. Each point carries its workload's number,
// placed where it overlaps no other label or marker; a table under the plot
// gives each numbered workload's times and errors.

// Writes a self-contained SVG (no scripts, no fonts beyond sans-serif)
// atomically; throws vkfuse::Error(Io).
void write_plot(const std::string& path, const std::vector<CellResult>& results, const std::string& device);

}  // namespace vkfuse::bench
