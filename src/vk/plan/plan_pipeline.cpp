// Plan::run, submit and collect: a cycle's round trip, whole or split so that
// two cycles overlap. A plan of cycles_in_flight 2 alternates between two
// lanes (plan_impl.hpp), each with its own upload, intermediates, read-back
// and command buffer:
//
//   host    upload c+1 | collect c, read c    | upload c+2 | collect c+1 ...
//   device  ...c       | c+1                  | c+2 ...
//
// so the host copies one cycle's frames in and its results out while the
// device works on the other. A lane is submitted again only once collected.
#include <string>

#include "vk/plan/plan_impl.hpp"
#include "vkfuse/core/error.hpp"

namespace vkfuse {

void Plan::submit(std::span<const FrameView> frames) {
    Impl& p = *impl_;
    p.finish_pending();  // the upload buffer may still be read by an asynchronous submit (vk/interop.hpp)
    if (p.in_flight.size() >= std::size_t(p.cfg.cycles_in_flight))
        throw Error(ErrorKind::InvalidArgument, "plan submit: " + std::to_string(p.in_flight.size()) +
                                                    " cycle(s) in flight already, as many as the plan keeps "
                                                    "(cycles_in_flight); collect() one first");
    Impl& lane = *p.next_lane;
    const PlanConfig& c = lane.cfg;
    if (lane.device_frames.handle() && frames.empty()) {
        lane.check_ready();
        lane.prepare_device_frames();
    } else {
        lane.upload_frames(frames);
    }
    // A plan whose skipping the host decides runs its detection here and
    // submits the fusion only where some sensor changed; one that decides on
    // the device submits the whole cycle and learns at collect() whom it fused.
    const bool host_decides = lane.skip && !lane.skip->on_device();
    lane.fused_last_run = true;
    if (host_decides) {
        // SkipPolicy::Static: the results of the sensors the last cycle fused
        // are kept before this one overwrites them (a skipping plan has one
        // lane, collected before this submit).
        if (lane.skip->statics())
            for (int s = 0; s < c.sensors; ++s)
                if (lane.skip->result_pending(s))
                    lane.skip->keep_result(s, c.want_fused ? &fused(s) : nullptr, !c.metrics.empty() ? metrics(s) : Metrics{});
        const std::vector<int> fused_sensors = lane.skip->detect();
        lane.skip->keep_frames(frames, fused_sensors);
        lane.compact(frames, fused_sensors);
        lane.fused_last_run = !fused_sensors.empty();
    }
    if (lane.fused_last_run) {
        lane.slot->submit();
        lane.submits += !lane.skip || host_decides;
        lane.submitted = true;
    }
    p.collected = false;
    p.in_flight.push_back(&lane);
    if (p.second_lane) p.next_lane = p.next_lane == &p ? p.second_lane.get() : &p;
}

void Plan::collect() {
    Impl& p = *impl_;
    if (p.in_flight.empty())
        throw Error(ErrorKind::InvalidArgument, "plan collect: no cycle in flight; submit() one first");
    Impl& lane = *p.in_flight.front();
    lane.wait_device();
    p.in_flight.pop_front();
    lane.complete();
    p.results = &lane;
    p.collected = true;
}

int Plan::in_flight() const { return int(impl_->in_flight.size()); }

void Plan::run(std::span<const FrameView> frames) {
    while (in_flight() > 0) collect();
    submit(frames);
    collect();
}

}  // namespace vkfuse
