// core/compensated_sum.hpp - Neumaier (improved Kahan-Babuska) summation. The
// metrics average up to 8192 x 8192 = 67M terms; a naive double sum loses ~7
// digits there, this keeps the result within a few ulp of the exact sum.
#pragma once
#include <cmath>
#include <cstddef>

namespace vkfuse::core {

class CompensatedSum {
public:
    void add(double x) {
        const double t = sum_ + x;
        // Whichever operand is larger lost the low bits of the other: keep them.
        compensation_ += std::abs(sum_) >= std::abs(x) ? (sum_ - t) + x : (x - t) + sum_;
        sum_ = t;
    }
    double value() const { return sum_ + compensation_; }

private:
    double sum_ = 0;
    double compensation_ = 0;
};

}  // namespace vkfuse::core
