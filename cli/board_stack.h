// The emulated board (`hitl target`, in this process) as a campaign flight's stack: bound on the
// ports the OS picks (it keeps its sockets), in lockstep, run on a thread for one flight.
#pragma once

#include <atomic>
#include <memory>
#include <thread>

#include "emulator/board.h"
#include "engine/campaign/flight_run.h"

namespace hitl::cli {

class EmulatedBoardStack : public campaign::FlightStack {
 public:
  /// `observer` gets the board's events (it must outlive the stack).
  explicit EmulatedBoardStack(target::Board::Observer& observer) : observer_(observer) {}
  ~EmulatedBoardStack() override { stop(); }
  Expected<Ports> start() override;
  void stop() override;
  campaign::StackFigures figures(const hil::SessionSnapshot& session) const override;

 private:
  target::Board::Observer& observer_;
  std::unique_ptr<target::Board> board_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace hitl::cli
