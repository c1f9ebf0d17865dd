#!/bin/bash
# A one-node Slurm on loopback (Debian 12: slurm-wlm 22.05, munge 0.5.15) to try the job-array
# scripts on one machine. Run as root in a container or VM you own; NOT part of CI (.ci/run never
# calls it). Undo with: scontrol shutdown; kill "$(cat /run/munge/munged.pid)".
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends slurmctld slurmd slurm-client munge
# The package creates /etc/munge/munge.key; munged needs its run folder (no systemd here).
mkdir -p /run/munge && chown munge:munge /run/munge && chmod 755 /run/munge
su -s /bin/sh munge -c /usr/sbin/munged
munge -n | unmunge > /dev/null
mkdir -p /var/spool/slurmctld /var/spool/slurmd /var/log/slurm
chown slurm:slurm /var/spool/slurmctld /var/log/slurm
# One node named after this host on 127.0.0.1, 2 CPUs, 8 GB (the merge job asks for 4 GB).
sed "s/\bvm\b/$(hostname)/g" "$here/loopback-slurm.conf" > /etc/slurm/slurm.conf
/usr/sbin/slurmctld
sleep 2
/usr/sbin/slurmd
sleep 2
sinfo
