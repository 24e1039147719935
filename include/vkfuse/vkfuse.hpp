// vkfuse/vkfuse.hpp - every public header, for a caller who wants them all.
// Each subsystem's headers stand alone too; a caller that uses one links its
// target (vkfuse::core, vkfuse::sensor, vkfuse::vk, vkfuse::rig) or vkfuse.
#pragma once
#include "vkfuse/version.hpp"  // generated: kVersion, VKFUSE_VERSION_MAJOR / MINOR / PATCH

// core: what to fuse, the CPU reference, images and their files
#include "vkfuse/core/error.hpp"
#include "vkfuse/core/fusion.hpp"
#include "vkfuse/core/image.hpp"
#include "vkfuse/core/io.hpp"
#include "vkfuse/core/metrics.hpp"
#include "vkfuse/core/reference.hpp"
#include "vkfuse/core/skip.hpp"

// vk: a Vulkan device and the plans recorded on it
#include "vkfuse/vk/context.hpp"
#include "vkfuse/vk/plan.hpp"
#include "vkfuse/vk/interop.hpp"  // a caller's own device, buffers, command buffers and shared memory

// sensor: cameras under switched LEDs, recorded datasets, the simulated DIGIT
#include "vkfuse/sensor/clock.hpp"
#include "vkfuse/sensor/dataset.hpp"
#include "vkfuse/sensor/digit.hpp"
#include "vkfuse/sensor/illumination.hpp"
#include "vkfuse/sensor/sensor.hpp"
#include "vkfuse/sensor/sim_digit.hpp"
#include "vkfuse/sensor/switching.hpp"

// rig: many sensors fused per cycle, the background model
#include "vkfuse/rig/background.hpp"
#include "vkfuse/rig/rig.hpp"

// study: which LED settings and fusion method serve a sensor best
#include "vkfuse/study/study.hpp"
