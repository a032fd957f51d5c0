#include "hqview/core/error_kind.h"

#include <exception>
#include <filesystem>
#include <new>

#include "hqview/core/error.h"
#include "hqview/core/stop.h"

namespace hq {

ErrorKind kind_of_current_exception() {
  try {
    throw;
  } catch (const ValueError&) {
    return ErrorKind::usage;
  } catch (const InputError&) {
    return ErrorKind::input;
  } catch (const EnvironmentError&) {
    return ErrorKind::environment;
  } catch (const Interrupted&) {
    return ErrorKind::interrupted;
  } catch (const std::filesystem::filesystem_error&) {
    return ErrorKind::environment;
  } catch (const std::bad_alloc&) {
    return ErrorKind::environment;
  } catch (...) {
    return ErrorKind::internal;
  }
}

}  // namespace hq
