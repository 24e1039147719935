// The DIGIT LED rig, calibrated (sim/led.hpp).
#include "sim/led.hpp"

namespace vkfuse::sim {

LightField light_field_terms(double x_mm, double y_mm) {
    const double x = x_mm / 10, y = y_mm / 10;
    return {1, x, y, x * x, x * y, y * y, x * x * x, x * x * y, x * y * y, y * y * y};
}

double evaluate(const LightField& field, double x_mm, double y_mm) {
    const LightField t = light_field_terms(x_mm, y_mm);
    double sum = 0;
    for (std::size_t j = 0; j < t.size(); ++j) sum += field[j] * t[j];
    return sum;
}

LedRig digit_led_rig() {
    LedRig rig;
    // Red (about 625 nm) and blue (465 nm) LEDs leak little into the other
    // filters; green (525 nm) sits between and leaks into both, most into blue.
    rig.crosstalk = {{{1.0, 0.10, 0.05}, {0.08, 1.0, 0.20}, {0.02, 0.25, 1.0}}};
    // Rim positions: a light-guide model (beam lobe times exp(-distance /
    // length), free position, lobe and length per LED) fitted to the same
    // frame puts the red LED at 294, green at 57 and blue at 190 degrees, close
    // to the 120 degrees apart they are mounted at.
    // Fields: fit_light_fields(landscape_from_portrait(digit_bg_tacto.png),
    // crosstalk above); tests/test_cpu_sim_calibration.cpp re-derives them.
    rig.leds[0] = {294, {117.527, 88.2802, -115.976, -52.3003, -9.92172, -69.1813, -74.839, 72.685, -67.9473, 81.8837}};
    rig.leds[1] = {57, {95.3221, 28.0137, 55.1348, -24.2782, -7.33405, -22.7366, -24.6492, -37.7113, -4.01214, -36.0038}};
    rig.leds[2] = {190, {80.0267, -21.8651, -57.9609, 9.05021, 13.7736, -36.2231, 60.9443, 41.1814, 21.2825, 38.2553}};
    return rig;
}

}  // namespace vkfuse::sim
