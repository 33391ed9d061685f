#include "acc_identification/model/parallel_tasks.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace acc
{
std::size_t effectiveThreadCount(std::size_t requested, std::size_t tasks)
{
  std::size_t threads = requested > 0 ? requested : std::thread::hardware_concurrency();
  threads = std::max<std::size_t>(threads, 1);
  return std::max<std::size_t>(std::min(threads, tasks), 1);
}

void runTasksInParallel(std::size_t count, std::size_t threads, const std::function<void(std::size_t)>& task,
                        const std::function<void(std::size_t, std::size_t)>& progress)
{
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;  // guards done, first_error and the progress calls
  std::size_t done = 0;
  std::exception_ptr first_error;
  auto worker = [&]() {
    for (std::size_t i = next++; i < count && !failed; i = next++)
    {
      try
      {
        task(i);
      }
      catch (...)
      {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!first_error)
          first_error = std::current_exception();
        failed = true;
        return;
      }
      const std::lock_guard<std::mutex> lock(mutex);
      ++done;
      if (progress)
        progress(done, count);
    }
  };
  std::vector<std::thread> pool;
  const std::size_t n = effectiveThreadCount(threads, count);
  for (std::size_t t = 1; t < n; ++t)
    pool.emplace_back(worker);
  worker();  // the calling thread is one of the n
  for (std::thread& thread : pool)
    thread.join();
  if (first_error)
    std::rethrow_exception(first_error);
}

}  // namespace acc
