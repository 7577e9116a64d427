#pragma once
// Child processes of the `drape` executable (the jobs of a batch): started with posix_spawn, their output to files.
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace drape::app {

// This executable (/proc/self/exe resolved), so that a job runs exactly the code of the batch that started it.
std::filesystem::path drapeExecutable();

// The first executable file named program in a folder of $PATH; empty when there is none.
std::filesystem::path findOnPath(const std::string& program);

// Starts executable with arguments, stdin from /dev/null and stdout, stderr into the two files (appended to when
// append, else truncated). Returns the process id; throws InputError when it cannot be started.
pid_t spawnProcess(const std::filesystem::path& executable, const std::vector<std::string>& arguments,
                   const std::filesystem::path& stdoutFile, const std::filesystem::path& stderrFile,
                   bool append = false);

// Waits for that child (retrying on EINTR) and returns its wait status as waitpid gives it.
int waitForProcess(pid_t pid);

// The exit status of a wait status: the process's own, or 128 + the signal that ended it (as a shell says).
int exitStatusOf(int waitStatus);

}  // namespace drape::app
