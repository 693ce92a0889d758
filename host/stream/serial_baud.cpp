// Baud rate through termios2 (TCGETS2/TCSETS2 with BOTHER): the only way to
// set rates that have no Bnnn constant, and exact for every rate. Kept in
// its own file because <asm/termbits.h> clashes with <termios.h>.
#include <asm/termbits.h>
#include <sys/ioctl.h>

namespace eskin::stream::detail {

// 0 on success, else errno-style failure (-1).
int set_baud_termios2(int fd, int baud) {
  struct termios2 t;
  if (ioctl(fd, TCGETS2, &t) != 0) return -1;
  t.c_cflag &= ~tcflag_t(CBAUD | (CBAUD << IBSHIFT));
  t.c_cflag |= BOTHER | (BOTHER << IBSHIFT);
  t.c_ispeed = speed_t(baud);
  t.c_ospeed = speed_t(baud);
  return ioctl(fd, TCSETS2, &t);
}

int get_baud_termios2(int fd) {
  struct termios2 t;
  if (ioctl(fd, TCGETS2, &t) != 0) return -1;
  return int(t.c_ospeed);
}

}  // namespace eskin::stream::detail
