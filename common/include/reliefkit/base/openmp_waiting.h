// ReliefKit — OpenMP threads that wait without taking a core from other programs.
#pragma once

namespace reliefkit {

/// Makes this process's OpenMP threads wait passively where nobody chose how they wait.
///
/// libgomp reads OMP_WAIT_POLICY and GOMP_SPINCOUNT once, when it is loaded — in MeshLab that is
/// before any ReliefKit plugin (MeshLab's own plugins load it) — and with neither set, a thread
/// that waits spins 300,000 times before it sleeps: milliseconds, on every parallel loop's end
/// and between loops. Beside another busy program the spinning threads hold the cores the working
/// ones need, and a filter of many short parallel loops ran ten times slower. libgomp spins only
/// 100 times while it manages more threads than the process has CPUs (its manual, GOMP_SPINCOUNT):
/// this keeps one extra OpenMP thread asleep for the life of the process, so that the count is
/// above the CPUs whenever a team uses them all, as OMP_WAIT_POLICY=PASSIVE would.
///
/// Nothing is done where OMP_WAIT_POLICY or GOMP_SPINCOUNT is set (the user chose), when the
/// OpenMP runtime is not libgomp, or a second time in one process (the first call marks the
/// process with RELIEFKIT_OPENMP_WAITING). Returns true when the extra thread is (now) parked.
bool wait_passively_in_openmp();

}  // namespace reliefkit
