// arrays.hpp - numpy arrays in and out of vkfuse, for the Python module.
// Frames come in as uint8 (scaled by 1/255, as a camera's), float32 or
// float64, shaped (H, W) or (H, W, C) with C 1 or 3; they are checked once
// here, and borrowed without a copy wherever the plan can read them as they
// are (C-contiguous uint8 or float32).
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "vkfuse/core/image.hpp"

namespace vkfuse::python {

namespace py = pybind11;

// K frames of one shape and element type, kept alive while views point into them.
struct Frames {
    std::vector<py::array> arrays;  // C-contiguous, uint8 or float32 (float64 converted)
    int height = 0, width = 0, channels = 0;
    bool gray = false;               // given as (H, W): results are (H, W) too
    PixelType type = PixelType::F32;

    // Views of the frames as a plan reads them (float64 frames converted to
    // float32 here, once).
    std::vector<FrameView> views();
    // Each frame in double precision, uint8 scaled by 1/255 (the reference path's input).
    std::vector<ImageD> images() const;
};

// Checks and borrows `frames` (a sequence of arrays; `what` names them in
// errors, e.g. "frames"). Throws Error(InvalidArgument / Shape) with one line
// naming the frame and the problem.
Frames to_frames(const py::sequence& frames, const std::string& what);
// One array, as to_frames would take it ("image", "background").
Frames to_frame(const py::handle& array, const std::string& what);

// A float32 array of shape (H, W) when gray, else (H, W, C), copied from img.
template <class T>
py::array_t<float> to_array(const BasicImage<T>& img, bool gray);

// Where S fused images go: float32 (S, H, W) when gray, else (S, H, W, C).
// `out`, when not None, must be exactly that (shape, float32, C order,
// writeable; else Error naming "out") and is filled in place; otherwise a
// new array.
py::array_t<float> fused_array(const py::object& out, int sensors, int height, int width, int channels, bool gray);
// img into sensor s's slot of fused_array's data (which may be written with
// the GIL released).
template <class T>
void put(float* fused, int s, const BasicImage<T>& img);

}  // namespace vkfuse::python
