// A test source with an anonymous namespace: check_test_unit_namespaces.py must reject it.
namespace {
int helper() { return 1; }
}  // namespace
