// study/table.hpp - every score of a study, and the analysis that reads them.
#pragma once
#include <cstddef>
#include <map>
#include <vector>

#include "vkfuse/study/study.hpp"

namespace vkfuse::study {

// Gains per (combination, method, object). Combinations are sets of two or
// more settings (indices, ascending); a method that does not take that many
// settings (channel-sum: exactly three) has no entry there.
struct Table {
    std::size_t methods = 0;
    std::size_t objects = 0;
    std::vector<std::vector<std::size_t>> combinations;
    std::vector<Gains> gains;        // [(combination * methods + method) * objects + object]
    std::vector<bool> scored;        // [combination * methods + method]
    std::vector<std::vector<Gains>> singles;  // [setting][object]: each frame as it is

    const Gains* at(std::size_t combination, std::size_t method) const {
        return scored[combination * methods + method] ? &gains[(combination * methods + method) * objects] : nullptr;
    }
};

// Whether m fuses any number of settings (channel-sum: exactly three), as the
// ranking method, the greedy search and the pairing need.
bool takes_any_count(const StudyMethod& m);

// The mean over objects.
Gains mean_gain(const Gains* per_object, std::size_t objects);

// What the table alone answers: the method summaries and best_method, the
// best pairs and their intersections, best_k and the best combination
// (result.settings, objects and methods' names are set before). Returns the
// method (an index into methods, the table's) the pairs are ranked by, and
// the greedy search uses: best_method, or where that one takes a fixed number
// of settings, the best of those that take any.
std::size_t analyse(const Table& table, const std::vector<StudyMethod>& methods, int top, StudyResult& result);

}  // namespace vkfuse::study
