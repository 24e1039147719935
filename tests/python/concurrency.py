"""Running one piece of test work on several threads at once."""
import threading


def in_threads(count, work):
    """work(i) for i in range(count), each on a thread of its own, all started before any is joined."""
    threads = [threading.Thread(target=work, args=(i,)) for i in range(count)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
