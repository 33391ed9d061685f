#pragma once

#include <cstddef>
#include <functional>

namespace acc
{
/// Runs task(i) for i in [0, count) on `threads` std::threads (0: hardware_concurrency), each
/// thread taking the next index when it is free. Results must be stored by index by the task, so
/// that they do not depend on which thread ran what. progress(done, total) is called after each
/// task, one call at a time (may be empty). An exception thrown by a task is rethrown here after
/// every thread has stopped (the first one thrown); the tasks not yet started are then skipped.
void runTasksInParallel(std::size_t count, std::size_t threads, const std::function<void(std::size_t)>& task,
                        const std::function<void(std::size_t, std::size_t)>& progress = {});

/// The number of threads to use for `requested` (0: hardware_concurrency, at least 1), never more
/// than there are tasks.
std::size_t effectiveThreadCount(std::size_t requested, std::size_t tasks);

}  // namespace acc
