// Ctrl-C, SIGTERM and SIGHUP during a run (every chapter): the first asks the
// run to stop after the frame in flight and write what it has (the report
// says it was interrupted, and after how many frames); the second quits at
// once, writing nothing, and removes a temporary file being written.
#pragma once
#include <string>

namespace rg {

void installInterruptHandlers();
bool interrupted();                  // a first signal has arrived
std::string interruptSignalName();   // "SIGINT", "SIGTERM" or "SIGHUP"; empty if none

// What an interrupted run wrote, for its last line ("after 12 of 1000
// frames; wrote a.png and a.json"); set by the code that writes the outputs.
void setInterruptedRunSummary(const std::string& summary);
std::string interruptedRunSummary();  // "nothing written" until set

// The temporary file being written now (files.cpp), which a second signal
// removes before quitting; nullptr: none.
void setFileInProgress(const char* path);

}  // namespace rg
