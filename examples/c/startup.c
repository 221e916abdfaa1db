/*
 * Minimal Cortex-M4F start-up for QEMU's mps2-an386: the vector table, a reset handler
 * that enables the FPU, copies .data, clears .bss, paints the stack (for the peak-stack
 * measurement), runs main and ends the run through semihosting with main's status. Faults
 * end the run with a failure status instead of hanging. Semihosting is called directly
 * (BKPT 0xAB, ARM's semihosting specification): SYS_OPEN of ":tt" for writing (the host's
 * standard output), SYS_WRITE for output, SYS_EXIT to stop.
 */
#include <stddef.h>
#include <stdint.h>

extern uint32_t _sidata[], _sdata[], _edata[], _sbss[], _ebss[], _sstack[], _estack[];
extern int main(void);

#define PAINT 0xa5a5a5a5u
#define SYS_OPEN 0x01u
#define SYS_WRITE 0x05u
#define SYS_EXIT 0x18u
#define ADP_STOPPED_APPLICATION_EXIT 0x20026u
#define ADP_STOPPED_RUN_TIME_ERROR 0x20023u

static uintptr_t semihost(uint32_t op, uintptr_t arg) {
    register uintptr_t r0 __asm("r0") = op;
    register uintptr_t r1 __asm("r1") = arg;
    __asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void startup_write0(const char *s);
size_t startup_stack_peak(void);
void Reset_Handler(void);
void Fault_Handler(void);

static uintptr_t console = (uintptr_t)-1;

/* Writes a NUL-terminated string to the host's standard output. */
void startup_write0(const char *s) {
    if (console == (uintptr_t)-1) {
        /* Mode 4 ("w") on the special name ":tt" is standard output. */
        uintptr_t open_args[3] = {(uintptr_t)":tt", 4, 3};
        console = semihost(SYS_OPEN, (uintptr_t)open_args);
    }
    size_t n = 0;
    while (s[n]) n++;
    uintptr_t write_args[3] = {console, (uintptr_t)s, n};
    semihost(SYS_WRITE, (uintptr_t)write_args);
}

/* QEMU ends with status 0 for an application exit and 1 for any other reason. */
__attribute__((noreturn)) static void stop(int ok) {
    semihost(SYS_EXIT, ok ? ADP_STOPPED_APPLICATION_EXIT : ADP_STOPPED_RUN_TIME_ERROR);
    for (;;) {
    }
}

void Fault_Handler(void) {
    startup_write0("FAULT\n");
    stop(0);
}

__attribute__((section(".vectors"), used)) void (*const vector_table[16])(void) = {
    (void (*)(void))_estack, Reset_Handler, Fault_Handler, Fault_Handler, Fault_Handler,
    Fault_Handler,           Fault_Handler, 0,             0,             0,
    0,                       Fault_Handler, Fault_Handler, 0,             Fault_Handler,
    Fault_Handler,
};

/* Bytes of stack used so far: from the top down to the deepest overwritten paint word. */
size_t startup_stack_peak(void) {
    uint32_t *p = _sstack;
    while (p < _estack && *p == PAINT) p++;
    return (size_t)((uint8_t *)_estack - (uint8_t *)p);
}

__attribute__((noreturn)) void Reset_Handler(void) {
    /* CPACR: full access to CP10 and CP11 (the FPU), before any floating-point code. */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm volatile("dsb\n\tisb" ::: "memory");
    for (uint32_t *s = _sidata, *d = _sdata; d < _edata;) *d++ = *s++;
    for (uint32_t *d = _sbss; d < _ebss;) *d++ = 0;
    uint32_t *sp;
    __asm volatile("mov %0, sp" : "=r"(sp));
    for (uint32_t *d = _sstack; d < sp - 16;) *d++ = PAINT;
    stop(main() == 0);
}
