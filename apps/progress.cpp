// Progress on stderr (apps/progress.hpp).
#include "progress.hpp"

#include <unistd.h>

#include <cmath>
#include <utility>

namespace thalassa::cli {
namespace {

constexpr int kProgressBarWidth = 24;  // characters of the terminal progress bar

}  // namespace

std::string duration_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  char text[32];
  if (s >= 3600)
    std::snprintf(text, sizeof text, "%ldh%02ldm%02lds", s / 3600, s / 60 % 60, s % 60);
  else if (s >= 60)
    std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(text, sizeof text, "%lds", s);
  return text;
}

ProgressBar::ProgressBar(int total, std::string unit, std::FILE* out)
    : total_(total), unit_(std::move(unit)), out_(out), tty_(isatty(fileno(out))) {}

void ProgressBar::skipped(const std::string& item, const std::string& why) {
  ++done_;
  if (tty_)
    draw(item, "skipped");
  else
    std::fprintf(out_, "%s [%d/%d]: skipped (%s)\n", item.c_str(), done_, total_, why.c_str());
}

void ProgressBar::done(const std::string& item, const std::string& detail, double seconds) {
  ++done_;
  ++worked_;
  seconds_ += seconds;
  if (tty_) {
    draw(item, detail);
  } else {
    std::fprintf(out_, "%s [%d/%d] %s | %.2f %s/s, %s left\n", item.c_str(), done_, total_,
                 detail.c_str(), rate(), unit_.c_str(), duration_text(left()).c_str());
  }
}

void ProgressBar::note(const std::string& message) {
  // On a terminal the bar's line is cleared first; the next step draws the bar again below.
  std::fprintf(out_, "%sthalassa: %s\n", tty_ ? "\r\033[K" : "", message.c_str());
  std::fflush(out_);
}

void ProgressBar::finish() {
  if (tty_) std::fputc('\n', out_);
  std::fflush(out_);
}

double ProgressBar::rate() const { return seconds_ > 0 ? worked_ / seconds_ : 0.0; }

// Steps still to go at the rate so far (skipped steps cost nothing, but are not known yet).
double ProgressBar::left() const { return worked_ > 0 ? (total_ - done_) / rate() : NAN; }

void ProgressBar::draw(const std::string& item, const std::string& detail) {
  const int filled = total_ > 0 ? done_ * kProgressBarWidth / total_ : kProgressBarWidth;
  const std::string bar = std::string(filled, '#') + std::string(kProgressBarWidth - filled, '-');
  std::fprintf(out_, "\r\033[K[%s] %d/%d  %.2f %s/s  %s left  %s %s", bar.c_str(), done_, total_,
               rate(), unit_.c_str(), duration_text(left()).c_str(), item.c_str(), detail.c_str());
  std::fflush(out_);
}

}  // namespace thalassa::cli
