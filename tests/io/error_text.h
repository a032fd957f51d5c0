#pragma once
// error_text<E>(f): the what() of the E that f() throws, or a marker saying
// that it threw something else or nothing. Lets error-path tests check the
// exception type and its exact "path:line: message" in one EXPECT_EQ.

#include <exception>
#include <string>
#include <typeinfo>

namespace hq::test {

template <class E, class F>
std::string error_text(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("<other exception ") + typeid(e).name() + ": " + e.what() + ">";
  } catch (...) {
    return "<unknown exception>";
  }
  return "<no exception>";
}

}  // namespace hq::test
