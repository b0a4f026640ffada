// lib/robot/peer_process.cpp and splitCommandLine (lib/components/peripheries.cpp): the peer
// program a communicator starts -- its words split without a shell, its environment, its exit
// status, and the end of its whole process group.
#include <catch2/catch.hpp>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "robot/peer_process.h"
#include "simbob/model.h"

using namespace simbob;

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> w;
  std::string problem;
  REQUIRE(splitCommandLine(line, &w, &problem));
  return w;
}

std::string problemOf(const std::string& line) {
  std::vector<std::string> w;
  std::string problem;
  CHECK_FALSE(splitCommandLine(line, &w, &problem));
  return problem;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string tempPath(const char* name) {
  return std::string(P_tmpdir) + "/simbob_peer_process_" + std::to_string(::getpid()) + "_" + name;
}

}  // namespace

TEST_CASE("splitCommandLine: blanks, quotes and backslashes, no shell") {
  CHECK(split("/usr/bin/python3 client.py") == std::vector<std::string>{"/usr/bin/python3", "client.py"});
  CHECK(split("  a \t b  ") == std::vector<std::string>{"a", "b"});
  CHECK(split("'a b' \"c d\" e\\ f") == std::vector<std::string>{"a b", "c d", "e f"});
  CHECK(split("x'y z'\"w\"") == std::vector<std::string>{"xy zw"});
  CHECK(split("'it\\'s") == std::vector<std::string>{"it\\s"});  // nothing is special inside '...'
  CHECK(split("\"say \\\"hi\\\" \\\\ \\n\"") == std::vector<std::string>{"say \"hi\" \\ \\n"});
  CHECK(split("'' x") == std::vector<std::string>{"", "x"});
  CHECK(split("$HOME *.py >out") == std::vector<std::string>{"$HOME", "*.py", ">out"});
  CHECK(problemOf("a 'b") == "a quote (') is not closed");
  CHECK(problemOf("a \"b") == "a quote (\") is not closed");
  CHECK(problemOf("a\\") == "a backslash ends the command line");
  CHECK(problemOf("   ") == "the command line holds no program");
}

TEST_CASE("PeerProcess: environment, folder and output; the exit status") {
  const std::string log = tempPath("env.log");
  robot::PeerProcess p;
  REQUIRE(p.start({"/bin/sh", "-c", "echo $SIMBOB_PORT $SIMBOB_KEY; pwd; echo err >&2; exit 3"}, "/",
                  {{"SIMBOB_PORT", "123"}, {"SIMBOB_KEY", "A B"}}, log) == "");
  std::string how;
  for (int i = 0; i < 500 && !p.exited(&how); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  CHECK(how == "exited with status 3");
  CHECK(slurp(log) == "123 A B\n/\nerr\n");
  std::remove(log.c_str());
}

TEST_CASE("PeerProcess: a program that cannot start says why") {
  robot::PeerProcess p;
  CHECK(p.start({"./surely-no-such-program"}, "", {}, "") ==
        "cannot run ./surely-no-such-program: No such file or directory");
  CHECK_FALSE(p.started());
  CHECK(p.start({"/bin/true"}, "/surely/no/such/folder", {}, "") ==
        "cannot enter the folder /surely/no/such/folder: No such file or directory");
}

TEST_CASE("PeerProcess: end() leaves nothing of the group, even a child that ignores SIGTERM") {
  const std::string pids = tempPath("pids");
  robot::PeerProcess p;
  // A child that ignores TERM (KILL ends it) and the program itself, which waits.
  REQUIRE(p.start({"/bin/sh", "-c",
                   "sh -c 'trap \"\" TERM; echo $$; while :; do sleep 0.05; done' >" + pids + " & sleep 300"},
                  "", {}, "") == "");
  pid_t child = 0;
  for (int i = 0; i < 500 && child == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::ifstream f(pids);
    f >> child;
  }
  REQUIRE(child > 0);
  const auto t0 = std::chrono::steady_clock::now();
  p.end(0, 0.2);
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(took < 2.0);
  // The child was reparented; once killed it may linger as a zombie for its new parent to reap.
  std::ifstream stat("/proc/" + std::to_string(child) + "/stat");
  std::string text;
  std::getline(stat, text);
  const bool gone = text.empty() || text.find(") Z ") != std::string::npos;
  CHECK(gone);
  std::remove(pids.c_str());
}

TEST_CASE("PeerProcess: the log keeps the head and the tail and names the cut") {
  const std::string log = tempPath("capped.log");
  robot::PeerProcess p;
  // 26 letters and a newline, 40 times (1080 bytes): 100 bytes of head, 50 of tail kept.
  REQUIRE(p.start({"/bin/sh", "-c", "i=0; while [ $i -lt 40 ]; do echo abcdefghijklmnopqrstuvwxyz; i=$((i+1)); done"},
                  "", {}, log, 100, 50) == "");
  p.end(5);
  std::string line;
  for (int i = 0; i < 40; ++i) line += "abcdefghijklmnopqrstuvwxyz\n";
  CHECK(slurp(log) ==
        line.substr(0, 100) +
            "\n[simbob: 930 bytes of the controller's output cut here; this log keeps the first 100 bytes "
            "and the last 50 bytes]\n" +
            line.substr(line.size() - 50));
  // Within head + tail nothing is cut.
  REQUIRE(p.start({"/bin/sh", "-c", "echo 12345"}, "", {}, log, 3, 3) == "");
  p.end(5);
  CHECK(slurp(log) == "12345\n");
  std::remove(log.c_str());
}
