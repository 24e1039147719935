// numpy arrays in and out of vkfuse (arrays.hpp).
#include "arrays.hpp"

#include <algorithm>

#include "vkfuse/core/error.hpp"

namespace vkfuse::python {
namespace {

enum class Element { U8, F32, F64 };

std::string name_of(const py::dtype& d) { return d.attr("name").cast<std::string>(); }

Element element_of(const py::array& a, const std::string& name) {
    const py::dtype d = a.dtype();
    if (d.kind() == 'u' && d.itemsize() == 1) return Element::U8;
    if (d.kind() == 'f' && d.itemsize() == 4) return Element::F32;
    if (d.kind() == 'f' && d.itemsize() == 8) return Element::F64;
    throw Error(ErrorKind::InvalidArgument,
                name + ": dtype " + name_of(d) + "; expected uint8, float32 or float64");
}

std::string shape_text(int h, int w, int c, bool gray) {
    return "(" + std::to_string(h) + ", " + std::to_string(w) + (gray ? "" : ", " + std::to_string(c)) + ")";
}

// `single`: one array named `what`, else frames named what[k].
Frames checked(const py::sequence& frames, const std::string& what, bool single) {
    Frames out;
    Element first = Element::F32;
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const std::string name = single ? what : what + "[" + std::to_string(k) + "]";
        py::array a = py::array::ensure(frames[k]);
        if (!a) throw Error(ErrorKind::InvalidArgument, name + ": not an array");
        const Element e = element_of(a, name);
        if (a.ndim() != 2 && a.ndim() != 3)
            throw Error(ErrorKind::Shape, name + ": " + std::to_string(a.ndim()) + " dimensions; expected (H, W) or (H, W, C)");
        const bool gray = a.ndim() == 2;
        const py::ssize_t h = a.shape(0), w = a.shape(1), c = gray ? 1 : a.shape(2);
        if (h < 1 || w < 1 || (c != 1 && c != 3) || h > (1 << 16) || w > (1 << 16))
            throw Error(ErrorKind::Shape, name + ": shape " + shape_text(int(std::min<py::ssize_t>(h, 1 << 20)),
                                                                   int(std::min<py::ssize_t>(w, 1 << 20)), int(c), gray) +
                                              "; expected H, W in 1..65536 and C 1 or 3");
        if (k == 0) {
            out.height = int(h), out.width = int(w), out.channels = int(c), out.gray = gray, first = e;
            out.type = e == Element::U8 ? PixelType::U8 : PixelType::F32;
        } else if (int(h) != out.height || int(w) != out.width || int(c) != out.channels || gray != out.gray) {
            throw Error(ErrorKind::Shape, name + ": shape " + shape_text(int(h), int(w), int(c), gray) + "; " + what +
                                              "[0] is " + shape_text(out.height, out.width, out.channels, out.gray));
        } else if (e != first) {
            throw Error(ErrorKind::InvalidArgument, name + ": dtype " + name_of(a.dtype()) + "; " + what + "[0] is " +
                                                        name_of(out.arrays[0].dtype()));
        }
        // C order, as the plan reads frames; a copy only where the caller's array is not.
        if (e == Element::U8) a = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(a);
        else if (e == Element::F32) a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
        else a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
        out.arrays.push_back(a);
    }
    if (out.arrays.empty()) throw Error(ErrorKind::InvalidArgument, what + ": no frames given");
    return out;
}

}  // namespace

Frames to_frames(const py::sequence& frames, const std::string& what) {
    if (py::isinstance<py::array>(frames))
        throw Error(ErrorKind::InvalidArgument, what + ": a sequence of arrays (one per frame), not one array");
    return checked(frames, what, false);
}

Frames to_frame(const py::handle& array, const std::string& what) {
    py::list one;
    one.append(array);
    return checked(one, what, true);
}

std::vector<FrameView> Frames::views() {
    std::vector<FrameView> out;
    for (py::array& a : arrays) {
        if (a.dtype().kind() == 'f' && a.dtype().itemsize() == 8)
            a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
        out.push_back({a.data(), height, width, channels, type});
    }
    return out;
}

std::vector<ImageD> Frames::images() const {
    std::vector<ImageD> out;
    for (const py::array& a : arrays) {
        ImageD img(height, width, channels);
        const std::size_t n = img.size();
        if (type == PixelType::U8) {
            const auto* p = static_cast<const std::uint8_t*>(a.data());
            for (std::size_t i = 0; i < n; ++i) img.data[i] = p[i] / 255.0;
        } else if (a.dtype().itemsize() == 4) {
            const auto* p = static_cast<const float*>(a.data());
            std::copy(p, p + n, img.data.begin());
        } else {
            const auto* p = static_cast<const double*>(a.data());
            std::copy(p, p + n, img.data.begin());
        }
        out.push_back(std::move(img));
    }
    return out;
}

template <class T>
py::array_t<float> to_array(const BasicImage<T>& img, bool gray) {
    std::vector<py::ssize_t> shape = {img.height, img.width};
    if (!gray) shape.push_back(img.channels);
    py::array_t<float> out(shape);
    float* p = out.mutable_data();
    std::transform(img.data.begin(), img.data.end(), p, [](T v) { return float(v); });
    return out;
}

template py::array_t<float> to_array(const BasicImage<float>&, bool);
template py::array_t<float> to_array(const BasicImage<double>&, bool);

py::array_t<float> fused_array(const py::object& out, int sensors, int height, int width, int channels, bool gray) {
    std::vector<py::ssize_t> shape = {sensors, height, width};
    if (!gray) shape.push_back(channels);
    if (out.is_none()) return py::array_t<float>(shape);
    std::string want = "(";
    for (std::size_t i = 0; i < shape.size(); ++i) want += (i ? ", " : "") + std::to_string(shape[i]);
    want += ")";
    if (!py::isinstance<py::array>(out)) throw Error(ErrorKind::InvalidArgument, "out: not a numpy array");
    py::array a = py::reinterpret_borrow<py::array>(out);
    const py::dtype d = a.dtype();
    if (d.kind() != 'f' || d.itemsize() != 4)
        throw Error(ErrorKind::InvalidArgument, "out: dtype " + name_of(d) + "; the engine writes float32");
    bool same = a.ndim() == py::ssize_t(shape.size());
    for (std::size_t i = 0; same && i < shape.size(); ++i) same = a.shape(py::ssize_t(i)) == shape[i];
    if (!same) throw Error(ErrorKind::Shape, "out: shape differs from the result's " + want);
    if (!(a.flags() & py::array::c_style)) throw Error(ErrorKind::InvalidArgument, "out: not C-contiguous");
    if (!a.writeable()) throw Error(ErrorKind::InvalidArgument, "out: read-only");
    return py::reinterpret_borrow<py::array_t<float>>(out);
}

template <class T>
void put(float* fused, int s, const BasicImage<T>& img) {
    float* p = fused + std::size_t(s) * img.data.size();
    std::transform(img.data.begin(), img.data.end(), p, [](T v) { return float(v); });
}

template void put(float*, int, const BasicImage<float>&);
template void put(float*, int, const BasicImage<double>&);

}  // namespace vkfuse::python
