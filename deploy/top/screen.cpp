#include "deploy/top/screen.hpp"

#include <curses.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <string>

#include "deploy/top/view_text.hpp"

namespace maptr::top {

namespace {

constexpr short kDeadColour = 1;
std::atomic<bool> g_interrupted{false};
void on_interrupt(int) { g_interrupted.store(true); }

/// The curses session: set up in the constructor, the terminal restored in the destructor.
class Curses {
 public:
  Curses() {
    initscr();
    cbreak();
    noecho();
    curs_set(0);
    keypad(stdscr, TRUE);
    timeout(static_cast<int>(1000.0 / kRefreshHz));
    if (has_colors()) {
      start_color();
      use_default_colors();
      init_pair(kDeadColour, COLOR_RED, -1);
    }
  }
  ~Curses() { endwin(); }
  Curses(const Curses&) = delete;
  Curses& operator=(const Curses&) = delete;
};

/// Dead agents in red: their cell in the detailed layout, their letter in the compact one.
void mark_dead(int row, const std::string& line) {
  const bool agents = line.size() > 2 && (line[0] == 'L' || line[0] == 'R');
  if (!agents || !has_colors()) return;
  const bool cells = line[1] >= '0' && line[1] <= '9';
  for (std::size_t at = 0; cells && (at = line.find(" dead ", at)) != std::string::npos; ++at) {
    const std::size_t cell = at / kCellWidth * kCellWidth;
    mvchgat(row, static_cast<int>(cell), kCellWidth - 2, A_BOLD, kDeadColour, nullptr);
  }
  if (line[1] == ' ')
    for (std::size_t at = 0; (at = line.find(state_letter(CellState::kDead), at)) != std::string::npos; ++at)
      mvchgat(row, static_cast<int>(at), 1, A_BOLD, kDeadColour, nullptr);
}

void draw(const FleetView& v, int events_back) {
  int rows = 0, cols = 0;
  getmaxyx(stdscr, rows, cols);
  const auto lines = layout(v, cols, rows, events_back);
  erase();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (i == 0) attron(A_REVERSE);
    mvaddnstr(static_cast<int>(i), 0, lines[i].c_str(), cols);
    if (i == 0) attroff(A_REVERSE);
    mark_dead(static_cast<int>(i), lines[i]);
  }
  refresh();
}

}  // namespace

int run_screen(Watch& w) {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  Curses session;
  int events_back = 0;  // the event list scrolled back this many events (0: the latest)
  while (!g_interrupted.load()) {
    w.poll();
    const int n = static_cast<int>(w.view().events().size());
    events_back = std::clamp(events_back, 0, std::max(0, n - 1));
    draw(w.view(), events_back);
    const int key = getch();  // waits at most one refresh period; KEY_RESIZE redraws at once
    if (key == 'q' || key == 'Q') break;
    if (key == KEY_UP) ++events_back;
    if (key == KEY_DOWN) --events_back;
    if (key == KEY_PPAGE) events_back += kEventsShown;
    if (key == KEY_NPAGE) events_back -= kEventsShown;
    if (key == KEY_END) events_back = 0;
  }
  return 0;
}

}  // namespace maptr::top
