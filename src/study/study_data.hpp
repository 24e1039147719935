// study/study_data.hpp - what a study reads from a dataset: per object one
// frame under each LED setting, and per setting the mean background.
#pragma once
#include <string>
#include <vector>

#include "vkfuse/core/image.hpp"
#include "vkfuse/sensor/dataset.hpp"

namespace vkfuse::study {

// Settings a study takes at most: combinations grow as n^5, and the dataset
// must not choose how much time and memory the study takes.
inline constexpr std::size_t kMaxSettings = 64;
// Objects, and the bytes of the frames held (objects x settings x H x W x 3),
// a study takes at most, for the same reason.
inline constexpr std::size_t kMaxObjects = 64;
inline constexpr std::size_t kMaxFrameBytes = std::size_t(2) << 30;

struct StudyData {
    int height = 0;
    int width = 0;
    // Every setting with a background, in recording order; each object has a
    // frame under each.
    std::vector<Illumination> settings;
    std::size_t static_setting = 0;  // every LED at its full level
    std::vector<std::string> objects;
    std::vector<std::vector<Frame>> frames;  // [object][setting]: the first frame recorded
    std::vector<Image> backgrounds;          // [setting]: the mean of its background frames
};

// Throws Error(InvalidArgument), the message starting with subject, for fewer
// than two or more than kMaxSettings settings, an object named twice, more
// than kMaxObjects objects, or frames beyond kMaxFrameBytes.
void check_study_size(std::size_t settings, const std::vector<std::string>& objects, int height, int width,
                      const std::string& subject);

// Reads the frames of sensor `serial` (empty: the dataset's first) and of
// `objects` (empty: every object that sensor pressed). Throws
// Error(InvalidArgument) naming the dataset for a missing sensor, object,
// background or frame, an object named twice, a dataset without the static
// setting or with fewer than two settings, or beyond the bounds above;
// frames that are missing on disk or of another shape throw as load_frame does.
StudyData load_study_data(const Dataset& dataset, const std::string& serial, const std::vector<std::string>& objects);

}  // namespace vkfuse::study
