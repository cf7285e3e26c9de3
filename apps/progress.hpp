// Progress of a long command on stderr (`thalassa fly`, `thalassa validate`): a bar redrawn in
// place on a terminal, else one line per step, for logs.
#pragma once

#include <cstdio>
#include <string>

namespace thalassa::cli {

// "42s", "3m05s", "1h02m03s"; "?" for a negative or non-finite time.
std::string duration_text(double seconds);

class ProgressBar {
 public:
  // `total` steps; `unit` names them in the rate ("frames" -> "2.50 frames/s"). The bar is drawn
  // in place when `out` is a terminal.
  ProgressBar(int total, std::string unit, std::FILE* out = stderr);

  // A step skipped at no cost (e.g. already written): "<item> [3/10]: skipped (<why>)".
  void skipped(const std::string& item, const std::string& why);
  // A step done in `seconds`: "<item> [3/10] <detail> | 2.50 frames/s, 2m48s left".
  void done(const std::string& item, const std::string& detail, double seconds);
  // A line of its own between steps ("thalassa: <message>"), which the bar does not draw over.
  void note(const std::string& message);
  // Ends the bar's line (on a terminal).
  void finish();

  int done_count() const { return done_; }      // done or skipped
  int worked_count() const { return worked_; }  // done
  int skipped_count() const { return done_ - worked_; }
  int total() const { return total_; }

 private:
  double rate() const;  // steps worked per second so far
  double left() const;  // seconds still to go at that rate (NaN before the first step worked)
  void draw(const std::string& item, const std::string& detail);

  int total_ = 0;
  std::string unit_;
  std::FILE* out_ = stderr;
  bool tty_ = false;
  int done_ = 0;    // steps done or skipped
  int worked_ = 0;  // steps done
  double seconds_ = 0.0;
};

}  // namespace thalassa::cli
