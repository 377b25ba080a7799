// The grader's wire format between the trusted test process and the worker that holds the
// student's code (tools/grader/worker.py, docs/grading.md "The worker").
//
// A message is a 4-byte length and that many bytes. Values are written in order, each type by
// one overload of put/get below: numbers raw, Eigen dense matrices as rows, cols and raw
// doubles, quaternions as their 4 coefficients, sparse matrices as compressed columns,
// std::vector and std::pair element by element, and the labs' structs field by field (the
// generated <lab>_rpc.h, from the lab's headers: tools/grader/stubs.py). Reading never trusts the
// other side: every count is non-negative and checked by division against what is left of the
// message (a product could wrap), every dimension is at most kMaxDim, every bool is re-made
// from a byte, and a message larger than kMaxMessage is refused.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace wbrpc {

constexpr std::uint32_t kMaxMessage = 64u << 20;  // bytes: larger is a protocol error
constexpr std::size_t kMaxText = 2048;            // bytes of an error message kept
// Rows, columns, non-zeros: at most what one message could fill with doubles, even where the
// dimension itself takes no bytes (a sparse matrix's rows, an empty matrix's other side),
// so that nothing the trusted side sizes from it (a dense copy, a column count) is huge.
constexpr std::int64_t kMaxDim = kMaxMessage / sizeof(double);

enum Kind : std::int32_t {
  kCall = 1,      // trusted -> worker: function id, arguments
  kResult = 2,    // worker -> trusted: the outputs, then the return value
  kError = 3,     // worker -> trusted: the lab's code threw (message)
  kCallback = 4,  // worker -> trusted: a callback (dynamics, force) with its arguments
  kCbResult = 5,  // trusted -> worker: the callback's outputs
  kCbError = 6,   // trusted -> worker: the callback threw
};

struct ProtocolError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Out {
  std::string buf = std::string(4, '\0');  // the length, filled in by Channel::send
  void raw(const void* p, std::size_t n) { buf.append(static_cast<const char*>(p), n); }
};

struct In {
  std::string buf;
  std::size_t pos = 0;
  void raw(void* d, std::size_t n) {
    if (buf.size() - pos < n) throw ProtocolError("message shorter than its contents");
    if (n) std::memcpy(d, buf.data() + pos, n);
    pos += n;
  }
  std::size_t left() const { return buf.size() - pos; }
};

// ---- numbers, enums, bools
template <class T>
std::enable_if_t<std::is_arithmetic_v<T> || std::is_enum_v<T>> put(Out& o, const T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    const unsigned char b = v ? 1 : 0;
    o.raw(&b, 1);
  } else {
    o.raw(&v, sizeof v);
  }
}
template <class T>
std::enable_if_t<std::is_arithmetic_v<T> || std::is_enum_v<T>> get(In& in, T& v) {
  if constexpr (std::is_same_v<T, bool>) {
    unsigned char b = 0;
    in.raw(&b, 1);
    v = b != 0;  // a bool is 0 or 1, whatever byte came
  } else {
    in.raw(&v, sizeof v);
  }
}

// n elements of at least `elem` bytes each must fit in what is left of the message: checked by
// division, never by a product that could wrap.
inline void check_count(In& in, std::int64_t n, std::size_t elem) {
  if (n < 0 || n > kMaxDim || std::uint64_t(n) > in.left() / (elem ? elem : 1))
    throw ProtocolError("a size larger than the message");
}

// The fewest bytes one value of T takes on the wire: what a vector's count is checked against
// (a count of 10^7 "structs" in a 10 MB message would otherwise allocate gigabytes first).
// The generated <lab>_rpc.h adds one for each of the lab's structs (the sum of its fields').
template <class T, class = void>
struct WireMin {
  static constexpr std::size_t value = 1;
};
template <class T>
struct WireMin<T, std::enable_if_t<std::is_arithmetic_v<T> || std::is_enum_v<T>>> {
  static constexpr std::size_t value = std::is_same_v<T, bool> ? 1 : sizeof(T);
};
template <class S, int R, int C, int O, int MR, int MC>
struct WireMin<Eigen::Matrix<S, R, C, O, MR, MC>> {
  static constexpr std::size_t value =
      16 + (R > 0 && C > 0 ? std::size_t(R) * std::size_t(C) * sizeof(S) : 0);
};
template <class S>
struct WireMin<Eigen::Quaternion<S>> {
  static constexpr std::size_t value = 16 + 4 * sizeof(S);
};
template <class A, class B>
struct WireMin<std::pair<A, B>> {
  static constexpr std::size_t value = WireMin<A>::value + WireMin<B>::value;
};
template <class T, class Al>
struct WireMin<std::vector<T, Al>> {
  static constexpr std::size_t value = 8;
};
template <>
struct WireMin<std::string> {
  static constexpr std::size_t value = 8;
};

// ---- Eigen dense matrices (fixed or dynamic size)
template <class S, int R, int C, int O, int MR, int MC>
void put(Out& o, const Eigen::Matrix<S, R, C, O, MR, MC>& m) {
  const std::int64_t r = m.rows(), c = m.cols();
  put(o, r), put(o, c);
  o.raw(m.data(), std::size_t(r * c) * sizeof(S));
}
template <class S, int R, int C, int O, int MR, int MC>
void get(In& in, Eigen::Matrix<S, R, C, O, MR, MC>& m) {
  std::int64_t r = 0, c = 0;
  get(in, r), get(in, c);
  if ((R != Eigen::Dynamic && r != R) || (C != Eigen::Dynamic && c != C) || r < 0 || c < 0 ||
      r > kMaxDim || c > kMaxDim)
    throw ProtocolError("a matrix of the wrong shape");
  // r c entries must fit in what is left: by division, never by a product that could wrap
  // (an empty matrix, r or c zero, takes no bytes whatever the other dimension).
  if (r > 0 && c > 0 &&
      (std::uint64_t(c) > in.left() / sizeof(S) ||
       std::uint64_t(r) > in.left() / sizeof(S) / std::uint64_t(c)))
    throw ProtocolError("a size larger than the message");
  m.resize(r, c);
  in.raw(m.data(), std::size_t(r) * std::size_t(c) * sizeof(S));
}

template <class S>
void put(Out& o, const Eigen::Quaternion<S>& q) {
  put(o, Eigen::Matrix<S, 4, 1>(q.coeffs()));
}
template <class S>
void get(In& in, Eigen::Quaternion<S>& q) {
  Eigen::Matrix<S, 4, 1> c;
  get(in, c);
  q.coeffs() = c;
}

// ---- sparse matrices: compressed columns (explicit zeros and order kept)
inline void put(Out& o, const Eigen::SparseMatrix<double>& a) {
  Eigen::SparseMatrix<double> m = a;
  m.makeCompressed();
  const std::int64_t r = m.rows(), c = m.cols(), nnz = m.nonZeros();
  put(o, r), put(o, c), put(o, nnz);
  o.raw(m.outerIndexPtr(), std::size_t(c + 1) * sizeof(int));
  o.raw(m.innerIndexPtr(), std::size_t(nnz) * sizeof(int));
  o.raw(m.valuePtr(), std::size_t(nnz) * sizeof(double));
}
inline void get(In& in, Eigen::SparseMatrix<double>& a) {
  std::int64_t r = 0, c = 0, nnz = 0;
  get(in, r), get(in, c), get(in, nnz);
  if (r < 0 || c < 0 || nnz < 0 || r > kMaxDim || c >= kMaxDim || nnz > kMaxDim)
    throw ProtocolError("a sparse matrix of the wrong shape");
  check_count(in, c + 1, sizeof(int));
  check_count(in, nnz, sizeof(int) + sizeof(double));
  if (std::uint64_t(c + 1) * sizeof(int) + std::uint64_t(nnz) * (sizeof(int) + sizeof(double)) >
      in.left())
    throw ProtocolError("a size larger than the message");
  std::vector<int> outer(static_cast<std::size_t>(c + 1)), inner(static_cast<std::size_t>(nnz));
  std::vector<double> values(static_cast<std::size_t>(nnz));
  in.raw(outer.data(), outer.size() * sizeof(int));
  in.raw(inner.data(), inner.size() * sizeof(int));
  in.raw(values.data(), values.size() * sizeof(double));
  // A malformed structure would make Eigen read out of bounds: check it first.
  if (outer[0] != 0 || std::int64_t(outer[std::size_t(c)]) != nnz)
    throw ProtocolError("bad sparse columns");
  for (std::int64_t k = 0; k < c; ++k)
    if (outer[std::size_t(k)] > outer[std::size_t(k + 1)])
      throw ProtocolError("bad sparse columns");
  for (int i : inner)
    if (i < 0 || i >= r) throw ProtocolError("a sparse row index out of range");
  for (std::int64_t k = 0; k < c;
       ++k)  // Eigen's compressed columns are sorted (it searches them)
    for (int p = outer[std::size_t(k)] + 1; p < outer[std::size_t(k + 1)]; ++p)
      if (inner[std::size_t(p - 1)] >= inner[std::size_t(p)])
        throw ProtocolError("a sparse column whose rows are not increasing");
  a = Eigen::Map<const Eigen::SparseMatrix<double>>(r, c, nnz, outer.data(), inner.data(),
                                                    values.data());
}

// ---- strings, vectors, pairs
inline void put(Out& o, const std::string& s) {
  put(o, std::int64_t(s.size()));
  o.raw(s.data(), s.size());
}
inline void get(In& in, std::string& s) {
  std::int64_t n = 0;
  get(in, n);
  check_count(in, n, 1);
  s.resize(std::size_t(n));
  in.raw(s.data(), s.size());
}
template <class A, class B>
void put(Out& o, const std::pair<A, B>& p) {
  put(o, p.first), put(o, p.second);
}
template <class A, class B>
void get(In& in, std::pair<A, B>& p) {
  get(in, p.first), get(in, p.second);
}
template <class T, class Al>
void put(Out& o, const std::vector<T, Al>& v) {
  put(o, std::int64_t(v.size()));
  for (const T& e : v) put(o, e);
}
template <class T, class Al>
void get(In& in, std::vector<T, Al>& v) {
  std::int64_t n = 0;
  get(in, n);
  check_count(in, n, WireMin<T>::value);  // every element takes at least that many bytes
  v.clear();
  v.resize(std::size_t(n));
  for (auto& e : v) {
    T x{};
    get(in, x);
    e = std::move(x);
  }
}

// Text from the other side, made printable and short (it ends up in a test's message).
inline std::string printable(const std::string& s) {
  std::string out;
  for (unsigned char c : s.substr(0, kMaxText)) {
    if (c == '\n' || c == '\t' || (c >= 0x20 && c < 0x7f)) {
      out += char(c);
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  if (s.size() > kMaxText) out += "[... " + std::to_string(s.size() - kMaxText) + " more bytes]";
  return out;
}

// A function of a point (wb::Potential, a field of a lab's struct) crosses as a callback: the
// trusted side keeps a copy of it and sends its index, the worker gets a proxy that asks the
// trusted side for each value (client.cpp and worker_main.cpp define these, one side each). The
// index is a value: it names that copy for the rest of the test, never a later function.
using PointFunction = std::function<double(const Eigen::Matrix<double, 2, 1>&)>;
void put(Out& o, const PointFunction& f);
void get(In& in, PointFunction& f);

// One end of the pipe pair: whole messages in, whole messages out.
class Channel {
 public:
  Channel(int in_fd, int out_fd) : in_(in_fd), out_(out_fd) {}
  void send(Out& o);
  In receive();  // throws ProtocolError on end of file or a malformed message

 private:
  int in_, out_;
};

// Argument passing: a parameter declared as a non-const lvalue reference is an output (sent
// to the worker and read back); every other one is an input only.
template <class A>
constexpr bool is_output_v =
    std::is_lvalue_reference_v<A> && !std::is_const_v<std::remove_reference_t<A>>;

}  // namespace wbrpc
