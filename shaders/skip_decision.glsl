// What a skipping plan that decides on the device (SkipPolicy::Idle,
// vk/plan/plan_skip.hpp) keeps in its two small buffers, for S = pc.sensors.
// SkipDecisionLayout in vk/plan/plan_skip.cpp is the host's view of the same.
//
// host_args (host-written):
//   [0]                       D, the fusion's indirect dispatches
//   [1, 10)                   the three gathers' groups (x, y, z per slot)
//   [10, 10 + S)              each sensor's background version (bumped by set_background)
//   [10 + S, 10 + S + 3 D)    each fusion dispatch's groups, z per sensor
// decision (written here, read back by the host):
//   [0, S)        the slot of sensor s, or NOT_FUSED
//   [S, 2S)       the sensor of slot j < F
//   [2S, 3S)      the slots whose background is copied this cycle
//   [3S, 4S)      the sensor and [4S, 5S) the version whose background slot j holds
//   [5S]          F, the fused sensors; [5S + 1] g, the first slot not its own
//                 sensor's; [5S + 2] the backgrounds copied
const uint NOT_FUSED = 0xffffffffu;
#define HOST_DISPATCHES 0u
#define HOST_GATHER(i) (1u + 3u * (i))
#define HOST_VERSION(s) (10u + (s))
#define HOST_FUSION(d) (10u + pc.sensors + 3u * (d))
#define SLOT_OF(s) (s)
#define SENSOR_OF(j) (pc.sensors + (j))
#define COPY_LIST(c) (2u * pc.sensors + (c))
#define HELD_SENSOR(j) (3u * pc.sensors + (j))
#define HELD_VERSION(j) (4u * pc.sensors + (j))
#define FUSED_COUNT (5u * pc.sensors)
#define FIRST_MOVED (5u * pc.sensors + 1u)
#define COPY_COUNT (5u * pc.sensors + 2u)
