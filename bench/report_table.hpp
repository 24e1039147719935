// The readable table on stdout, printed row by row as cells finish.
#pragma once
#include <cstdio>

#include "result.hpp"

namespace vkfuse::bench {

void print_table_header(std::FILE* out);
// One line per cell (a skipped cell says why); with --profile a second line of stage times.
void print_row(std::FILE* out, const CellResult& r);
// The workload's peer, once after its cells: its time per sensor and its error.
void print_peer(std::FILE* out, const PeerResult& p);

}  // namespace vkfuse::bench
