#!/usr/bin/env bash
# The hardware-in-the-loop test (ctest -L hil): boots Debian's kernel in QEMU
# with an initramfs holding busybox, the kernel's USB and video modules, the
# emulated DIGIT and the DIGIT tests, runs tests/hil/in_vm.sh inside and exits
# with its status.
#
#   run_hil.sh CACHE_DIR EMULATOR HIL_TESTS VKFUSE [PYTHON_DIR]
#
# PYTHON_DIR (the build's python/, holding the vkfuse package): the guest
# also gets this host's python3, its standard library and numpy, and drives
# the emulated DIGIT from Python once (tests/hil/rig_from_python.py).
# The kernel package is downloaded once into CACHE_DIR (apt-get download:
# never installed as this machine's kernel). It is bookworm-backports' 6.12
# (Debian 12's 6.1 carries vhci_hcd too; 6.12 is what the emulator was
# developed against). QEMU runs without KVM (TCG).
set -euo pipefail
cache=$1 emulator=$2 tests=$3 vkfuse=$4 python_dir=${5:-}
here=$(cd "$(dirname "$0")" && pwd)
start=$SECONDS
phase() { printf 'hil: %-34s %4d s\n' "$1" $((SECONDS - start)); }

need() {
    for tool in "$@"; do
        command -v "$tool" >/dev/null || { echo "hil: $tool is missing (bash tools/quickstart.sh test installs it)" >&2; exit 1; }
    done
}
need qemu-system-x86_64 busybox xz dpkg-deb apt-get
busybox_bin=$(command -v busybox)

# 1. The kernel: the newest 6.12 image bookworm-backports offers, cached.
mkdir -p "$cache"
kernel_dir="$cache/kernel"
if [ ! -f "$kernel_dir/ok" ]; then
    if ! grep -rqs bookworm-backports /etc/apt/sources.list /etc/apt/sources.list.d/; then
        echo "hil: bookworm-backports is not among apt's sources (bash tools/quickstart.sh test adds it)" >&2
        exit 1
    fi
    package=$(apt-cache depends -t bookworm-backports linux-image-amd64 2>/dev/null |
              awk '/Depends: linux-image-6\.12/ {print $2; exit}')
    [ -n "$package" ] || { echo "hil: no 6.12 kernel image in bookworm-backports" >&2; exit 1; }
    rm -rf "$kernel_dir" && mkdir -p "$kernel_dir"
    (cd "$kernel_dir" && apt-get download "$package" >/dev/null 2>&1) ||
        { echo "hil: apt-get download $package failed" >&2; exit 1; }
    dpkg-deb -x "$kernel_dir"/*.deb "$kernel_dir/root"
    rm -f "$kernel_dir"/*.deb
    touch "$kernel_dir/ok"
fi
vmlinuz=$(ls "$kernel_dir"/root/boot/vmlinuz-* | head -1)
modules=$(ls -d "$kernel_dir"/root/lib/modules/* | head -1)
phase "kernel ($(basename "$modules"))"

# 2. The initramfs. Modules in load order; each one's own dependencies (its
#    modinfo "depends") must come before it, which is checked, not assumed.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
root="$work/root"
mkdir -p "$root"/{bin,proc,sys,dev,tmp,mods,hil}
cp "$busybox_bin" "$root/bin/busybox"
loaded=" "
i=0
for m in usb_common usbcore usbip_core vhci_hcd mc videobuf2_common videodev videobuf2_v4l2 \
         videobuf2_memops videobuf2_vmalloc uvc uvcvideo; do
    file=$(find "$modules/kernel" -name "$m.ko*" -o -name "${m//_/-}.ko*" | head -1)
    [ -n "$file" ] || { echo "hil: module $m is not in $(basename "$modules")" >&2; exit 1; }
    i=$((i + 1))
    out="$root/mods/$(printf %02d $i)_$m.ko"
    case $file in *.xz) xz -dc "$file" >"$out" ;; *) cp "$file" "$out" ;; esac
    deps=$(tr '\0' '\n' <"$out" | sed -n 's/^depends=//p' | tr ',' ' ')
    for d in $deps; do
        case $loaded in *" ${d//-/_} "*) ;; *) echo "hil: $m needs $d, which is not loaded before it" >&2; exit 1 ;; esac
    done
    loaded="$loaded$m "
done
# Each program's or shared object's libraries, at their own paths in the guest.
copy_libraries() {
    ldd "$1" 2>/dev/null | awk '/=> \// {print $3} /^[ \t]*\/lib/ {print $1}' | while read -r lib; do
        [ -e "$root$lib" ] && continue
        mkdir -p "$root$(dirname "$lib")"
        cp -L "$lib" "$root$lib"
    done
}
for b in "$emulator" "$tests" "$vkfuse" "$(command -v v4l2-compliance || true)" "$(command -v v4l2-ctl || true)"; do
    [ -n "$b" ] || continue
    cp "$b" "$root/hil/"
    copy_libraries "$b"
done
cp "$here/in_vm.sh" "$root/hil/in_vm.sh"
if [ -n "$python_dir" ]; then
    python=$(readlink -f /usr/bin/python3)
    stdlib=$(/usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_paths()["stdlib"])')
    numpy=$(/usr/bin/python3 -c 'import numpy, os; print(os.path.dirname(numpy.__file__))')
    mkdir -p "$root/usr/bin" "$root$(dirname "$numpy")" "$root/hil/python"
    cp "$python" "$root/usr/bin/python3"
    copy_libraries "$python"
    # The standard library without its tests and tools (cp -a keeps the
    # byte-code caches valid), numpy without its tests, and the vkfuse package.
    mkdir -p "$root$(dirname "$stdlib")"
    (cd "$(dirname "$stdlib")" && tar -cf - --exclude=test --exclude=tests --exclude=idlelib --exclude=tkinter \
        --exclude=ensurepip --exclude=lib2to3 --exclude=pydoc_data --exclude='config-*' "$(basename "$stdlib")") |
        (cd "$root$(dirname "$stdlib")" && tar -xf -)
    (cd "$(dirname "$numpy")" && tar -cf - --exclude=tests numpy) | (cd "$root$(dirname "$numpy")" && tar -xf -)
    cp -a "$python_dir/vkfuse" "$root/hil/python/"
    find "$root$stdlib/lib-dynload" "$root$numpy" "$root/hil/python" -name '*.so' | while read -r so; do
        copy_libraries "$so"
    done
    cp "$here/rig_from_python.py" "$root/hil/"
fi
cat >"$root/init" <<'INIT'
#!/bin/busybox sh
/bin/busybox --install -s /bin
mount -t proc proc /proc; mount -t sysfs sys /sys; mount -t devtmpfs dev /dev; mount -t tmpfs tmp /tmp
for m in /mods/*.ko; do insmod "$m" || echo "hil: insmod $m failed"; done
cd /hil && PATH=/hil:/bin sh /hil/in_vm.sh
echo "hil-exit-status $?"
poweroff -f
INIT
chmod +x "$root/init"
(cd "$root" && find . | busybox cpio -o -H newc 2>/dev/null | gzip -1 >"$work/initrd.gz")
phase "initramfs ($(du -h "$work/initrd.gz" | cut -f1))"

# 3. Boot, run, read the status back from the console.
log="$cache/console.log"
boot() {
    timeout 840 qemu-system-x86_64 -cpu max -smp 2 -m 1536 -no-reboot -nographic \
        -kernel "$vmlinuz" -initrd "$work/initrd.gz" -append "console=ttyS0 quiet panic=-1" </dev/null >"$log" 2>&1 || true
}
boot
# The guest kernel itself, under QEMU's emulated CPU, rarely panics while it
# boots (an int3 in early text patching, before /init runs): that says
# nothing of vkfuse, so the machine is booted once more, and said so.
if grep -q "Kernel panic" "$log" && ! grep -q "^hil:\|hil-exit-status" "$log"; then
    cp "$log" "$log.panic"
    echo "hil: the guest kernel panicked while booting (console: $log.panic); booting it once more"
    boot
fi
tr -d '\r' <"$log" | sed -n '/^hil\|^\[ *RUN\|^\[ *OK\|^\[ *FAILED\|^\[==\|^\[ *PASSED\|Failure\|Expected\|Which is\|exception\|error\|v4l2-compliance\|Total for\|digit-emulator\|^{/p' | grep -v '^hil-exit-status'
status=$(tr -d '\r' <"$log" | sed -n 's/^hil-exit-status \([0-9]*\).*/\1/p' | tail -1)
phase "virtual machine"
[ -n "$status" ] || { echo "hil: the virtual machine did not finish (console: $log)" >&2; exit 1; }
exit "$status"
