// The pipelines a C++ user would write with OpenCV's own API, as the Python
// peer (bench/peers/pipelines.py) writes them with numpy: Laplacian pyramid
// fusion with pyrDown/pyrUp (docs/spec.md's rules: detail max-abs, ties to the
// lowest frame; base mean), Brovey and channel-sum with OpenCV's per-element
// operations, then the three metrics. vkfuse-bench runs it with the Python
// peer's command line and reads the same one-line JSON answer:
//
//   vkfuse-bench-peer-opencv --method laplacian --levels 4 --runs 20
//       --max-seconds 60 --background bg.npy --out fused.npy f0.npy f1.npy f2.npy
//
// Every Mat is allocated by the warm-up cycle and reused; OpenCV uses 2
// threads (the bench's hosts have 2 cores). Exit status 2 with one line on
// bad arguments or unreadable files.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace {

struct Args {
    std::string method;
    int levels = 4, runs = 20;
    double max_seconds = 60;
    std::string background, out;
    std::vector<std::string> frames;
};

double number(const std::string& option, const std::string& text) {
    std::size_t used = 0;
    double v = 0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || !std::isfinite(v))
        throw std::invalid_argument(option + ": not a number: '" + text + "'");
    return v;
}

int whole_number(const std::string& option, const std::string& text) {
    const double v = number(option, text);
    if (v != std::floor(v) || v < 1 || v > 1e6) throw std::invalid_argument(option + ": not a count >= 1: '" + text + "'");
    return int(v);
}

Args parse(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string k = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(k + " needs a value");
            return argv[++i];
        };
        if (k == "--method") {
            a.method = value();
            if (a.method != "laplacian" && a.method != "brovey" && a.method != "channel-sum")
                throw std::invalid_argument("--method " + a.method + ": the C++ peer runs laplacian, brovey, channel-sum");
        } else if (k == "--levels") {
            a.levels = whole_number(k, value());
        } else if (k == "--runs") {
            a.runs = whole_number(k, value());
        } else if (k == "--max-seconds") {
            a.max_seconds = number(k, value());
        } else if (k == "--background") {
            a.background = value();
        } else if (k == "--out") {
            a.out = value();
        } else if (k.rfind("--", 0) == 0) {
            throw std::invalid_argument("unknown option " + k);
        } else {
            a.frames.push_back(k);
        }
    }
    if (a.method.empty() || a.frames.size() < 2 || a.background.empty() || a.out.empty())
        throw std::invalid_argument("needs --method, --background, --out and two or more frames");
    if (a.method == "channel-sum" && a.frames.size() != 3)
        throw std::invalid_argument("channel-sum needs three frames");
    return a;
}

cv::Mat as_mat(vkfuse::Image& img) {
    if (img.channels != 3) throw std::invalid_argument("frames must have 3 channels");
    return cv::Mat(img.height, img.width, CV_32FC3, img.data.data());
}

// The Brovey threshold of docs/spec.md, s >= 1e-6 in exact arithmetic: the smallest float
// that is >= 1e-6 (float(1e-6) rounds below it).
float brovey_threshold() {
    const float t = 1e-6f;
    return double(t) >= 1e-6 ? t : std::nextafter(t, 1.0f);
}

// One cycle's buffers, reused from cycle to cycle.
struct Pipeline {
    std::string method;
    int K, L;
    std::vector<std::vector<cv::Mat>> gauss, lap;  // [frame][level]
    std::vector<cv::Mat> fused, up, abs_best, abs_k, mask, positive;
    cv::Mat sum, weighted, product, dark, result, luma, gx, gy, magnitude, diff;

    Pipeline(std::string m, int frames, int levels) : method(std::move(m)), K(frames), L(levels) {
        gauss.assign(std::size_t(K), std::vector<cv::Mat>(std::size_t(L) + 1));
        lap.assign(std::size_t(K), std::vector<cv::Mat>(std::size_t(L)));
        fused.resize(std::size_t(L) + 1);
        up.resize(std::size_t(L));
        abs_best.resize(std::size_t(L));
        abs_k.resize(std::size_t(L));
        mask.resize(std::size_t(L));
        positive.resize(std::size_t(K));
    }

    const cv::Mat& fuse(const std::vector<cv::Mat>& frames) {
        if (method == "laplacian") return laplacian(frames);
        if (method == "brovey") return brovey(frames);
        result.create(frames[0].size(), CV_32FC3);  // channel-sum: R of frame 0, G of 1, B of 2
        const int from_to[] = {0, 0, 4, 1, 8, 2};
        cv::mixChannels(frames.data(), 3, &result, 1, from_to, 3);
        return result;
    }

    const cv::Mat& laplacian(const std::vector<cv::Mat>& frames) {
        for (int k = 0; k < K; ++k) {
            auto& g = gauss[std::size_t(k)];
            g[0] = frames[std::size_t(k)];
            for (int l = 0; l < L; ++l) {
                cv::pyrDown(g[std::size_t(l)], g[std::size_t(l) + 1]);
                cv::pyrUp(g[std::size_t(l) + 1], up[std::size_t(l)], g[std::size_t(l)].size());
                cv::subtract(g[std::size_t(l)], up[std::size_t(l)], lap[std::size_t(k)][std::size_t(l)]);
            }
        }
        for (int l = 0; l < L; ++l) {  // max-abs: a later frame wins only when strictly larger
            cv::Mat& best = fused[std::size_t(l)];
            lap[0][std::size_t(l)].copyTo(best);
            cv::absdiff(best, cv::Scalar::all(0), abs_best[std::size_t(l)]);
            for (int k = 1; k < K; ++k) {
                const cv::Mat& c = lap[std::size_t(k)][std::size_t(l)];
                cv::absdiff(c, cv::Scalar::all(0), abs_k[std::size_t(l)]);
                cv::compare(abs_k[std::size_t(l)], abs_best[std::size_t(l)], mask[std::size_t(l)], cv::CMP_GT);
                c.copyTo(best, mask[std::size_t(l)]);
                abs_k[std::size_t(l)].copyTo(abs_best[std::size_t(l)], mask[std::size_t(l)]);
            }
        }
        gauss[0][std::size_t(L)].copyTo(sum);  // base: the mean of the tops
        for (int k = 1; k < K; ++k) cv::add(sum, gauss[std::size_t(k)][std::size_t(L)], sum);
        sum.convertTo(fused[std::size_t(L)], CV_32F, 1.0 / K);
        fused[std::size_t(L)].copyTo(result);
        for (int l = L - 1; l >= 0; --l) {
            cv::pyrUp(result, up[std::size_t(l)], fused[std::size_t(l)].size());
            cv::add(up[std::size_t(l)], fused[std::size_t(l)], result);
        }
        return result;
    }

    // sum_k p_k I_k / s with p_k = max(I_k, 0), s = sum_k p_k; the mean of
    // the frames where s < 1e-6.
    const cv::Mat& brovey(const std::vector<cv::Mat>& frames) {
        for (int k = 0; k < K; ++k) {
            cv::max(frames[std::size_t(k)], 0.0, positive[std::size_t(k)]);
            cv::multiply(positive[std::size_t(k)], frames[std::size_t(k)], product);
            if (k == 0) {
                positive[0].copyTo(sum);
                product.copyTo(weighted);
            } else {
                cv::add(sum, positive[std::size_t(k)], sum);
                cv::add(weighted, product, weighted);
            }
        }
        cv::divide(weighted, sum, result);
        cv::compare(sum, brovey_threshold(), dark, cv::CMP_LT);
        if (cv::countNonZero(dark.reshape(1)) == 0) return result;
        frames[0].copyTo(product);
        for (int k = 1; k < K; ++k) cv::add(product, frames[std::size_t(k)], product);
        product.convertTo(product, CV_32F, 1.0 / K);
        product.copyTo(result, dark);
        return result;
    }

    // numpy.gradient along both axes of the luma, mean magnitude; RMS contrast;
    // mean |I - B| over every sample.
    void metrics(const cv::Mat& img, const cv::Mat& background, double out[3]) {
        cv::transform(img, luma, cv::Matx13f(0.299f, 0.587f, 0.114f));
        const int h = luma.rows, w = luma.cols;
        gx.create(h, w, CV_32F);
        gy.create(h, w, CV_32F);
        for (int y = 0; y < h; ++y) {
            const float* row = luma.ptr<float>(y);
            const float* above = luma.ptr<float>(std::max(y - 1, 0));
            const float* below = luma.ptr<float>(std::min(y + 1, h - 1));
            float* dx = gx.ptr<float>(y);
            float* dy = gy.ptr<float>(y);
            for (int x = 0; x < w; ++x) {
                dx[x] = w == 1 ? 0.0f : x == 0 ? row[1] - row[0] : x == w - 1 ? row[x] - row[x - 1] : (row[x + 1] - row[x - 1]) * 0.5f;
                dy[x] = h == 1 ? 0.0f : y == 0 ? below[x] - row[x] : y == h - 1 ? row[x] - above[x] : (below[x] - above[x]) * 0.5f;
            }
        }
        cv::magnitude(gx, gy, magnitude);
        out[0] = cv::mean(magnitude)[0];
        cv::Scalar mean, stddev;
        cv::meanStdDev(luma, mean, stddev);
        out[1] = stddev[0];
        cv::absdiff(img, background, diff);
        const cv::Scalar d = cv::mean(diff);
        out[2] = (d[0] + d[1] + d[2]) / 3.0;
    }
};

std::string peer_name(const std::string& method) {
    return std::string("opencv-c++ ") + CV_VERSION + (method == "laplacian" ? " pyrDown/pyrUp" : "");
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Args a = parse(argc, argv);
        std::vector<vkfuse::Image> images;
        for (const auto& f : a.frames) images.push_back(vkfuse::io::read_image(f));
        vkfuse::Image bg_image = vkfuse::io::read_image(a.background);
        std::vector<cv::Mat> frames;
        for (auto& img : images) frames.push_back(as_mat(img));
        const cv::Mat background = as_mat(bg_image);
        for (const auto& f : frames)
            if (f.size() != background.size()) throw std::invalid_argument("frames and background differ in size");
        cv::setNumThreads(2);
        Pipeline p(a.method, int(frames.size()), a.levels);
        double m[3];
        using clock = std::chrono::steady_clock;
        auto start = clock::now();
        p.metrics(p.fuse(frames), background, m);  // warm-up: allocations, thread pool
        const double first = std::chrono::duration<double>(clock::now() - start).count();
        const int runs = std::max(5, std::min(a.runs, int(a.max_seconds / std::max(first, 1e-9))));
        std::vector<double> times;
        for (int r = 0; r < runs; ++r) {
            start = clock::now();
            p.metrics(p.fuse(frames), background, m);
            times.push_back(std::chrono::duration<double, std::milli>(clock::now() - start).count());
        }
        vkfuse::Image out(p.result.rows, p.result.cols, 3);
        std::copy_n(p.result.ptr<float>(0), out.data.size(), out.data.data());
        vkfuse::io::write_image(a.out, out);
        std::vector<double> sorted = times;
        std::sort(sorted.begin(), sorted.end());
        const double median = sorted.size() % 2 ? sorted[sorted.size() / 2]
                                                : (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2]) / 2;
        std::printf("{\"peer\": \"%s\", \"median_ms\": %.17g, \"min_ms\": %.17g, \"max_ms\": %.17g, \"runs\": %d, "
                    "\"sharpness\": %.17g, \"contrast\": %.17g, \"background_diff\": %.17g}\n",
                    peer_name(a.method).c_str(), median, sorted.front(), sorted.back(), runs, m[0], m[1], m[2]);
        return 0;
    } catch (const std::exception& e) {  // vkfuse::Error, cv::Exception and bad arguments alike
        const std::string what = e.what();  // cv::Exception's ends in a newline
        std::fprintf(stderr, "vkfuse-bench-peer-opencv: %s\n", what.substr(0, what.find('\n')).c_str());
        return 2;
    }
}
