// The pipeline a C++ user would write with OpenCV's own API: Laplacian pyramid
// fusion with pyrDown/pyrUp (SPEC.md's rules: detail max-abs, ties to the
// lowest frame; base mean), then the three metrics. vkfuse-bench runs it like
// bench/peers/pipelines.py, with the same command line and the same one-line
// JSON answer:
//
//   vkfuse-bench-peer-opencv --method laplacian --levels 4 --runs 20
//       --max-seconds 60 --background bg.npy --out fused.npy f0.npy f1.npy f2.npy
//
// Every Mat is allocated once, before the timed loop, and reused; OpenCV uses
// 2 threads (the bench's hosts have 2 cores). Exit status 2 with one line on
// bad arguments or unreadable files.
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "vkfuse/error.hpp"
#include "vkfuse/io.hpp"

namespace {

struct Args {
    int levels = 4, runs = 20;
    double max_seconds = 60;
    std::string background, out;
    std::vector<std::string> frames;
};

Args parse(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string k = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(k + " needs a value");
            return argv[++i];
        };
        if (k == "--method") {
            if (const std::string m = value(); m != "laplacian")
                throw std::invalid_argument("--method " + m + ": the C++ peer runs laplacian only");
        } else if (k == "--levels") {
            a.levels = std::stoi(value());
        } else if (k == "--runs") {
            a.runs = std::stoi(value());
        } else if (k == "--max-seconds") {
            a.max_seconds = std::stod(value());
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
    if (a.frames.size() < 2 || a.background.empty() || a.out.empty() || a.levels < 1 || a.runs < 1)
        throw std::invalid_argument("needs --background, --out, --levels >= 1, --runs >= 1 and two or more frames");
    return a;
}

cv::Mat as_mat(vkfuse::Image& img) {
    if (img.channels != 3) throw std::invalid_argument("frames must have 3 channels");
    return cv::Mat(img.height, img.width, CV_32FC3, img.data.data());
}

// One cycle's buffers, allocated once.
struct Pipeline {
    int K, L;
    std::vector<std::vector<cv::Mat>> gauss, lap;  // [frame][level]
    std::vector<cv::Mat> fused, up, abs_best, abs_k, mask;
    cv::Mat top_sum, result, luma, gx, gy, magnitude, diff;

    Pipeline(const std::vector<cv::Mat>& frames, int levels) : K(int(frames.size())), L(levels) {
        gauss.assign(std::size_t(K), std::vector<cv::Mat>(std::size_t(L) + 1));
        lap.assign(std::size_t(K), std::vector<cv::Mat>(std::size_t(L)));
        fused.resize(std::size_t(L) + 1);
        up.resize(std::size_t(L));
        abs_best.resize(std::size_t(L));
        abs_k.resize(std::size_t(L));
        mask.resize(std::size_t(L));
    }

    cv::Mat fuse(const std::vector<cv::Mat>& frames) {
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
        gauss[0][std::size_t(L)].copyTo(top_sum);  // base: the mean of the tops
        for (int k = 1; k < K; ++k) cv::add(top_sum, gauss[std::size_t(k)][std::size_t(L)], top_sum);
        top_sum.convertTo(fused[std::size_t(L)], CV_32F, 1.0 / K);
        fused[std::size_t(L)].copyTo(result);
        for (int l = L - 1; l >= 0; --l) {
            cv::pyrUp(result, up[std::size_t(l)], fused[std::size_t(l)].size());
            cv::add(up[std::size_t(l)], fused[std::size_t(l)], result);
        }
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
        cv::setNumThreads(2);
        Pipeline p(frames, a.levels);
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
        std::printf("{\"peer\": \"opencv-c++ %s pyrDown/pyrUp\", \"median_ms\": %.17g, \"min_ms\": %.17g, "
                    "\"max_ms\": %.17g, \"runs\": %d, \"sharpness\": %.17g, \"contrast\": %.17g, "
                    "\"background_diff\": %.17g}\n",
                    CV_VERSION, median, sorted.front(), sorted.back(), runs, m[0], m[1], m[2]);
        return 0;
    } catch (const std::exception& e) {  // vkfuse::Error, cv::Exception and bad arguments alike
        std::fprintf(stderr, "vkfuse-bench-peer-opencv: %s\n", e.what());
        return 2;
    }
}
