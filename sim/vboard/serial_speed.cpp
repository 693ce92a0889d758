// termios2 (TCGETS2) lives in <asm/termbits.h>, whose struct termios clashes
// with glibc's <termios.h>: this file includes only the former.
#include <asm/termbits.h>
#include <sys/ioctl.h>

namespace eskin::vboard {

double termios2_output_speed(int fd) {
  struct termios2 t {};
  if (ioctl(fd, TCGETS2, &t) != 0) return 0;
  return double(t.c_ospeed);
}

}  // namespace eskin::vboard
