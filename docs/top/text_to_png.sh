#!/bin/sh
# Renders a terminal capture (`tmux capture-pane -p`, COLS x ROWS characters) to a PNG with
# gnuplot's cairo terminal, one text label per line in a monospaced font.
# usage: docs/top/text_to_png.sh CAPTURE.txt OUT.png [COLS] [ROWS]
set -eu
in=$1
out=$2
cols=${3:-80}
rows=${4:-24}
char_w=8
line_h=17
script=$(mktemp)
trap 'rm -f "$script"' EXIT
{
  echo "set terminal pngcairo size $((cols * char_w + 16)),$((rows * line_h + 16)) font 'DejaVu Sans Mono,10' background '#101418' noenhanced"
  echo "set output '$out'"
  echo "unset border; unset tics; unset key; set margins 0,0,0,0"
  echo "set xrange [0:1]; set yrange [0:1]"
  # Agent cells (38 characters each, "L3   dead ...") are labelled one by one, a dead one in red.
  awk -v rows="$rows" -v w="$((cols * char_w + 16))" -v cw="$char_w" '
    function label(text, col, y, colour) {
      printf "set label \"%s\" at screen %f,%f left textcolor rgb \"%s\"\n", text, (8 + col * cw) / w, y, colour;
    }
    {
      gsub(/["\\]/, "'"'"'");
      y = 1 - (NR - 0.5) / rows;
      if (NR == 1) {
        printf "set object 1 rect from screen 0,%f to screen 1,%f fc rgb \"#a3be8c\" fs solid noborder behind\n", y - 0.5 / rows, y + 0.5 / rows;
        label($0, 0, y, "#101418");
      } else if ($0 ~ /^[LR][0-9]+ /) {
        for (c = 0; c < length($0); c += 38) {
          cell = substr($0, c + 1, 38);
          label(cell, c, y, cell ~ / dead / ? "#ff6b6b" : "#d8dee9");
        }
      } else label($0, 0, y, "#d8dee9");
    }' "$in"
  echo "plot NaN"
} >"$script"
gnuplot "$script"
