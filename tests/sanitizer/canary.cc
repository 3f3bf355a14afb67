// sanitizer_canary MODE: does one thing the sanitizer build must catch, so the build's tests show
// the instrumentation is really on and fatal: heap-overflow, signed-overflow, leak.
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

int main(int argc, char** argv) {
  const char* mode = argc > 1 ? argv[1] : "";
  volatile int index = argc + 7;  // 8 or more: opaque to the optimiser
  if (std::strcmp(mode, "heap-overflow") == 0) {
    int* a = new int[8];
    std::memset(a + index, 1, sizeof(int));  // through libc: AddressSanitizer's interceptor sees it
    std::printf("%d\n", a[0]);
    delete[] a;
  } else if (std::strcmp(mode, "signed-overflow") == 0) {
    volatile int big = INT_MAX - 1 + index / 8;
    std::printf("%d\n", big + index);
  } else if (std::strcmp(mode, "leak") == 0) {
    volatile char* lost = static_cast<char*>(std::malloc(1000 + index));
    lost[0] = 1;
    lost = nullptr;
  } else {
    std::fprintf(stderr, "usage: sanitizer_canary heap-overflow|signed-overflow|leak\n");
    return 2;
  }
  std::printf("not caught\n");
  return 0;
}
