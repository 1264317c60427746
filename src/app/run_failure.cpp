#include "app/run_failure.hpp"

#include <new>

#include "core/error.hpp"

namespace vdc {

Failure failure_of(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const UsageError& e) {
    return {kExitBadInput, "", e.what()};
  } catch (const InputError& e) {
    return {kExitBadInput, "", e.what()};
  } catch (const SimulationError& e) {
    return {kExitSimulationFailed, "simulation failed", e.what()};
  } catch (const OutputError& e) {
    return {kExitSimulationFailed, "writing the results failed", e.what()};
  } catch (const std::bad_alloc&) {
    return {kExitSimulationFailed, "out of memory", "an allocation failed"};
  } catch (const std::exception& e) {  // a fault of vdcloth's own or of the system, not of the input
    return {kExitSimulationFailed, "unexpected error", e.what()};
  }
}

}  // namespace vdc
