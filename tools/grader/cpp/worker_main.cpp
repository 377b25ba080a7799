// The worker's main loop (worker.h): `<lab>-worker <read fd> <write fd>`.
#include <cstdlib>
#include <string>

#include "worker.h"

namespace wbrpc {

static Channel* channel = nullptr;
Channel& worker_channel() { return *channel; }

void handle_call(In& in) {
  std::int32_t id = -1;
  get(in, id);
  try {
    dispatch(id, in);
  } catch (const ProtocolError&) {
    throw;
  } catch (const std::exception& e) {
    Out o;
    put(o, kError), put(o, std::string(e.what()));
    worker_channel().send(o);
  } catch (...) {
    Out o;
    put(o, kError), put(o, std::string("an exception that is not a std::exception"));
    worker_channel().send(o);
  }
}

// A function of a point whose values come from the trusted side (wb_rpc.h). The id names a
// copy the trusted side keeps for the whole test (client.h, Session::points): a copy of
// this proxy kept by the student's code from an earlier call computes that call's function,
// as a kept std::function would linked directly.
void get(In& in, PointFunction& f) {
  std::int32_t id = -1;
  get(in, id);
  if (id < 0) {
    f = nullptr;
    return;
  }
  f = [id](const Eigen::Matrix<double, 2, 1>& x) {
    Out o;
    put(o, kCallback), put(o, std::int32_t(4)), put(o, id), put(o, x);
    worker_channel().send(o);
    In in = wait_callback();
    double value = 0;
    get(in, value);
    return value;
  };
}
void put(Out&, const PointFunction&) { throw ProtocolError("a function sent to the test"); }

In wait_callback() {
  for (;;) {
    In in = worker_channel().receive();
    std::int32_t kind = 0;
    get(in, kind);
    if (kind == kCbResult) return in;
    if (kind == kCbError) {
      std::string what;
      get(in, what);
      throw CallbackFailed(what);
    }
    if (kind != kCall) throw ProtocolError("an unknown message");
    handle_call(in);  // the callback called the lab again
  }
}

}  // namespace wbrpc

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  static wbrpc::Channel ch(std::atoi(argv[1]), std::atoi(argv[2]));
  wbrpc::channel = &ch;
  for (;;) {
    wbrpc::In in;
    try {
      in = ch.receive();
    } catch (const wbrpc::ProtocolError&) {
      return 0;  // the test process is done
    }
    std::int32_t kind = 0;
    wbrpc::get(in, kind);
    if (kind != wbrpc::kCall) return 3;
    try {
      wbrpc::handle_call(in);
    } catch (const wbrpc::ProtocolError&) {
      return 0;  // the test process stopped in the middle of a call
    }
  }
}
