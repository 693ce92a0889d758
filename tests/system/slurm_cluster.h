// A one-node Slurm cluster for the system tests (munged, slurmctld and
// slurmd from Debian's slurm-wlm, a generated slurm.conf and munge key in a
// temporary directory, ports of its own), stopped by its pids.
#pragma once

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "host/bench/text_file.h"

// A one-node Slurm cluster in a temporary directory; stopped by its pids.
// Polls `cond` until it holds (true) or `timeout` has passed (false, after
// one last look): a wait on a condition, never a fixed sleep.
template <class Cond>
bool wait_until(Cond cond, std::chrono::milliseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!cond()) {
    if (std::chrono::steady_clock::now() >= end) return cond();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

class SlurmCluster {
 public:
  explicit SlurmCluster(const std::filesystem::path& dir) : dir_(dir) {
    const int base = 20000 + int(::getpid() % 10000) * 2;  // ports of our own
    std::filesystem::create_directories(dir / "state");
    std::filesystem::create_directories(dir / "spool");
    std::filesystem::permissions(dir, std::filesystem::perms(0755));
    {
      std::ofstream key(dir / "munge.key", std::ios::binary);
      std::ifstream rnd("/dev/urandom", std::ios::binary);
      std::vector<char> b(1024);
      rnd.read(b.data(), std::streamsize(b.size()));
      key.write(b.data(), std::streamsize(b.size()));
    }
    std::filesystem::permissions(dir / "munge.key", std::filesystem::perms::owner_read);
    const std::string d = dir.string();
    std::ofstream(dir / "slurm.conf")
        << "ClusterName=eskintest\nSlurmctldHost=localhost\n"
        << "SlurmctldPort=" << base << "\nSlurmdPort=" << base + 1 << "\n"
        << "AuthType=auth/munge\nCredType=cred/munge\nAuthInfo=socket=" << d << "/munge.sock\n"
        << "SlurmUser=root\nSlurmdUser=root\nStateSaveLocation=" << d << "/state\n"
        << "SlurmdSpoolDir=" << d << "/spool\nSlurmctldPidFile=" << d << "/slurmctld.pid\n"
        << "SlurmdPidFile=" << d << "/slurmd.pid\nSlurmctldLogFile=" << d << "/slurmctld.log\n"
        << "SlurmdLogFile=" << d << "/slurmd.log\nProctrackType=proctrack/linuxproc\n"
        << "TaskPlugin=task/none\nSelectType=select/cons_tres\nSelectTypeParameters=CR_Core\n"
        // Array tasks start as a CPU frees, not on the scheduler's default
        // 3 s cadence for batch jobs (batch_sched_delay).
        << "SchedulerType=sched/builtin\nSchedulerParameters=batch_sched_delay=0\n"
        << "JobCompType=jobcomp/none\n"
        << "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\n"
        << "MpiDefault=none\nReturnToService=2\n"
        // sbatch --wait polls every 2 s while that is under a third of
        // MinJobAge, and otherwise backs off to 8 and 32 s (the default 300
        // s age): most of a short array's run would be sbatch asleep. A
        // finished job stays listed 6 s, three polls.
        << "MinJobAge=6\n"
        << "NodeName=localhost NodeHostname=localhost CPUs=2 State=UNKNOWN\n"
        << "PartitionName=eskin Nodes=localhost Default=YES MaxTime=INFINITE State=UP\n";
    conf_ = d + "/slurm.conf";
    ok_ = sh("munged --socket=" + d + "/munge.sock --key-file=" + d + "/munge.key --pid-file=" + d +
             "/munged.pid --log-file=" + d + "/munged.log --seed-file=" + d + "/munge.seed --force") &&
          sh("slurmctld -f " + conf_) && sh("slurmd -f " + conf_ + " -N localhost");
    ok_ = ok_ && wait_until([this] { return idle(); }, std::chrono::seconds(30));
  }
  // Stops the daemons it started (by their pid files): SIGTERM, up to 10 s
  // to exit, then SIGKILL; then removes the directory.
  ~SlurmCluster() {
    for (const char* pid : {"slurmd.pid", "slurmctld.pid", "munged.pid"}) {
      std::ifstream f(dir_ / pid);
      long p = 0;
      if (!(f >> p) || p <= 1) continue;
      ::kill(pid_t(p), SIGTERM);
      if (!wait_until([p] { return ::kill(pid_t(p), 0) != 0; }, std::chrono::seconds(10)))
        ::kill(pid_t(p), SIGKILL);
    }
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  bool ok() const { return ok_; }
  const std::string& conf() const { return conf_; }
  std::string logs() const {
    return eskin::bench::read_text((dir_ / "slurmctld.log").string()) + eskin::bench::read_text((dir_ / "slurmd.log").string()) + eskin::bench::read_text((dir_ / "munged.log").string());
  }

 private:
  static bool sh(const std::string& cmd) { return std::system((cmd + " > /dev/null 2>&1").c_str()) == 0; }
  bool idle() const {
    return std::system(("SLURM_CONF=" + conf_ + " sinfo -h -o %t 2>/dev/null | grep -q idle").c_str()) == 0;
  }
  std::filesystem::path dir_;
  std::string conf_;
  bool ok_ = false;
};

